// Implements levelset/JawLevelSets.h; what it computes, its rules and its contract are documented there.
#include "levelset/JawLevelSets.h"

#include "io/Error.h"
#include "levelset/InsideOverlap.h"
#include "levelset/MeshToLevelSet.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace jawmesh {

namespace {

/// The bone's band widths: wide within kBoneWideBandMarginMm of each tooth's bounding box.
BandWidths boneBandWidths(const JawSurfaces& surfaces, double voxelMm, double boneBandVoxels, double boneFarBandVoxels) {
    BandWidths widths{boneBandVoxels, boneFarBandVoxels, {}};  // bandDistance caps the far one at the wide one
    const auto index = [&](double mm, bool up) {
        return int(up ? std::ceil((mm + kBoneWideBandMarginMm) / voxelMm) : std::floor((mm - kBoneWideBandMarginMm) / voxelMm));
    };
    for (const auto& [unn, mesh] : surfaces.teeth) {
        if (mesh.triangles.empty()) continue;
        const BBox box = boundingBox(mesh);
        widths.wideBoxes.emplace_back(openvdb::Coord(index(box.min.x(), false), index(box.min.y(), false), index(box.min.z(), false)),
                                      openvdb::Coord(index(box.max.x(), true), index(box.max.y(), true), index(box.max.z(), true)));
    }
    return widths;
}

}  // namespace

JawLevelSets jawLevelSets(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm, double boneBandVoxels,
                          double boneFarBandVoxels, double toothBandVoxels, Progress& progress) {
    auto levelSet = [&](const SurfaceMesh& mesh, const BandWidths& widths, Label label, const std::string& source) {
        try {
            MeshToLevelSetStats stats;
            openvdb::FloatGrid::Ptr grid = meshToLevelSet(mesh, voxelMm, widths, stats, progress);
            grid->setName(labelName(label));
            return grid;
        } catch (const Error& e) {
            throw Error(source, e.reason());
        }
    };
    JawLevelSets sets;
    sets.bone = levelSet(surfaces.bone, boneBandWidths(surfaces, voxelMm, boneBandVoxels, boneFarBandVoxels),
                         boneLabel(surfaces.jaw), boneSource(jawCase));
    const double toothBand = std::max(boneBandVoxels, toothBandVoxels);
    for (const auto& [unn, mesh] : surfaces.teeth)
        sets.teeth[unn] = levelSet(mesh, BandWidths{toothBand, toothBand, {}}, toothLabel(unn), toothSource(jawCase, unn));
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
