// Implements levelset/JawLevelSets.h; what it computes, its rules and its contract are documented there.
#include "levelset/JawLevelSets.h"

#include "io/Error.h"
#include "io/ParallelInOrder.h"
#include "levelset/InsideOverlap.h"
#include "levelset/MeshToLevelSet.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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

/// Teeth in contact overlap a little and the carving splits them; a large shared volume is a
/// segmentation error (one tooth exported twice, two teeth merged) that would mesh silently wrong.
/// The pairs at once; the error of the first pair in the order of the teeth. Only cancellation is
/// taken from `progress` (its bar has finished the level sets).
void refuseMergedTeeth(const JawLevelSets& sets, const JawCase& jawCase, const Progress& progress) {
    std::vector<std::pair<int, int>> pairs;  // (UNN, UNN)
    for (auto a = sets.teeth.begin(); a != sets.teeth.end(); ++a)
        for (auto b = std::next(a); b != sets.teeth.end(); ++b) pairs.emplace_back(a->first, b->first);
    CancelOnlyProgress quiet(progress);
    parallelForFirstErrorInOrder(pairs.size(), quiet, [&](std::size_t i) {
        const auto [a, b] = pairs[i];
        const double shared = insideOverlapFraction(*sets.teeth.at(a), *sets.teeth.at(b));
        if (shared > kHeavyToothOverlapFraction)
            throw Error(toothSource(jawCase, b), "overlaps " + toothSource(jawCase, a) + " by " +
                                                     std::to_string(static_cast<int>(shared * 100 + 0.5)) +
                                                     "% of the smaller tooth's volume: the same tooth exported twice, or two "
                                                     "teeth segmented into each other? Fix the segmentation.");
    });
}

}  // namespace

JawLevelSets jawLevelSets(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm, double boneBandVoxels,
                          double boneFarBandVoxels, double toothBandVoxels, Progress& progress) {
    // The bone and the teeth at once: each is parallel inside, but their serial steps (orientation,
    // sorts) left a core idle in turn. Each grid depends on its surface alone, so the threads
    // change nothing; the stage's bar counts triangles done (the inner stages would interleave).
    struct Job {
        const SurfaceMesh* mesh;
        BandWidths widths;
        Label label;
        std::string source;
    };
    std::vector<Job> jobs{{&surfaces.bone, boneBandWidths(surfaces, voxelMm, boneBandVoxels, boneFarBandVoxels),
                           boneLabel(surfaces.jaw), boneSource(jawCase)}};
    const double toothBand = std::max(boneBandVoxels, toothBandVoxels);
    for (const auto& [unn, mesh] : surfaces.teeth)
        jobs.push_back({&mesh, BandWidths{toothBand, toothBand, {}}, toothLabel(unn), toothSource(jawCase, unn)});
    std::vector<std::size_t> triangles;  // the bar's weights
    for (const Job& job : jobs) triangles.push_back(job.mesh->triangles.size());
    std::vector<openvdb::FloatGrid::Ptr> grids(jobs.size());
    ProgressStage stage(progress, "level sets");
    CancelOnlyProgress quiet(progress);
    parallelForFirstErrorInOrder(jobs.size(), progress, [&](std::size_t j) {
        const Job& job = jobs[j];
        try {
            MeshToLevelSetStats stats;
            grids[j] = meshToLevelSet(*job.mesh, voxelMm, job.widths, stats, quiet);
            grids[j]->setName(labelName(job.label));
        } catch (const Error& e) {
            throw Error(job.source, e.reason());
        }
    }, triangles);
    JawLevelSets sets;
    sets.bone = grids[0];
    std::size_t j = 1;
    for (const auto& [unn, mesh] : surfaces.teeth) sets.teeth[unn] = grids[j++];
    refuseMergedTeeth(sets, jawCase, progress);
    return sets;
}

}  // namespace jawmesh
