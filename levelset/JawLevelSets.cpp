// Implements levelset/JawLevelSets.h; what it computes, its rules and its contract are documented there.
#include "levelset/JawLevelSets.h"

#include "io/Error.h"
#include "levelset/InsideOverlap.h"
#include "levelset/MeshToLevelSet.h"

#include <algorithm>
#include <string>

namespace jawmesh {

JawLevelSets jawLevelSets(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm, double boneBandVoxels,
                          double toothBandVoxels, Progress& progress) {
    auto levelSet = [&](const SurfaceMesh& mesh, double bandVoxels, Label label, const std::string& source) {
        try {
            openvdb::FloatGrid::Ptr grid = meshToLevelSet(mesh, voxelMm, bandVoxels, progress);
            grid->setName(labelName(label));
            return grid;
        } catch (const Error& e) {
            throw Error(source, e.reason());
        }
    };
    JawLevelSets sets;
    sets.bone = levelSet(surfaces.bone, boneBandVoxels, boneLabel(surfaces.jaw), boneSource(jawCase));
    const double toothBand = std::max(boneBandVoxels, toothBandVoxels);
    for (const auto& [unn, mesh] : surfaces.teeth) sets.teeth[unn] = levelSet(mesh, toothBand, toothLabel(unn), toothSource(jawCase, unn));
    // Teeth in contact overlap a little and the carving splits them; a large shared volume is a
    // segmentation error (one tooth exported twice, two teeth merged) that would mesh silently wrong.
    for (auto a = sets.teeth.begin(); a != sets.teeth.end(); ++a)
        for (auto b = std::next(a); b != sets.teeth.end(); ++b) {
            progress.checkCancelled();
            const double shared = insideOverlapFraction(*a->second, *b->second);
            if (shared > kHeavyToothOverlapFraction)
                throw Error(toothSource(jawCase, b->first),
                            "overlaps " + toothSource(jawCase, a->first) + " by " +
                                std::to_string(static_cast<int>(shared * 100 + 0.5)) +
                                "% of the smaller tooth's volume: the same tooth exported twice, or two teeth "
                                "segmented into each other? Fix the segmentation.");
        }
    return sets;
}

}  // namespace jawmesh
