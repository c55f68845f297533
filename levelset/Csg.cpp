#include "levelset/Csg.h"

#include "io/Error.h"

#include <openvdb/tools/Composite.h>
#include <openvdb/tools/LevelSetRebuild.h>

#include <cmath>
#include <string>

namespace jawmesh {
namespace {

/// Adapts our Progress to OpenVDB's interrupter interface.
struct Interrupter : openvdb::util::NullInterrupter {
    explicit Interrupter(Progress& p) : progress(p) {}
    bool wasInterrupted(int percent = -1) override {
        if (percent >= 0) progress.update(percent / 100.0);
        return progress.cancelled();
    }
    Progress& progress;
};

openvdb::FloatGrid::Ptr asLevelSet(openvdb::FloatGrid::Ptr g, const openvdb::FloatGrid& like) {
    g->setTransform(like.transform().copy());
    g->setGridClass(openvdb::GRID_LEVEL_SET);
    g->setName(like.getName());
    return g;
}

}  // namespace

double uniformVoxelSizeMm(const openvdb::FloatGrid& grid) {
    if (!grid.transform().hasUniformScale())
        throw Error("level set '" + grid.getName() + "' has a non-uniform transform");
    return grid.voxelSize()[0];
}

double bandHalfWidthMm(const openvdb::FloatGrid& grid) {
    const double bg = grid.background();
    if (!(bg > 0.0)) throw Error("grid '" + grid.getName() + "' is not a level set (background <= 0)");
    return bg;
}

void requireSameTransform(const openvdb::GridBase& a, const openvdb::GridBase& b, const char* what) {
    if (a.transform() != b.transform())
        throw Error(std::string(what) + ": grids '" + a.getName() + "' and '" + b.getName() +
                    "' do not share one transform (voxel size / origin)");
}

openvdb::FloatGrid::Ptr csgUnion(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
    requireSameTransform(a, b, "csgUnion");
    return asLevelSet(openvdb::tools::csgUnionCopy(a, b), a);
}

openvdb::FloatGrid::Ptr csgIntersection(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
    requireSameTransform(a, b, "csgIntersection");
    return asLevelSet(openvdb::tools::csgIntersectionCopy(a, b), a);
}

openvdb::FloatGrid::Ptr csgDifference(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
    requireSameTransform(a, b, "csgDifference");
    return asLevelSet(openvdb::tools::csgDifferenceCopy(a, b), a);
}

namespace {
openvdb::FloatGrid::Ptr rebuildAt(const openvdb::FloatGrid& grid, double isoMm, double exVoxels, double inVoxels,
                                  Progress& progress) {
    uniformVoxelSizeMm(grid);
    bandHalfWidthMm(grid);
    if (!(exVoxels >= 1.0) || !(inVoxels >= 1.0)) throw Error("level set band half width must be >= 1 voxel");
    Interrupter interrupter(progress);
    openvdb::FloatGrid::Ptr out;
    try {
        out = openvdb::tools::levelSetRebuild(grid, float(isoMm), float(exVoxels), float(inVoxels), nullptr,
                                              &interrupter);
    } catch (const openvdb::Exception& e) {
        throw Error("level set '" + grid.getName() + "': rebuild failed: " + e.what());
    }
    progress.checkCancelled();
    return asLevelSet(out, grid);
}
}  // namespace

openvdb::FloatGrid::Ptr renormalizeLevelSet(const openvdb::FloatGrid& grid, double exteriorHalfWidthVoxels,
                                            double interiorHalfWidthVoxels, Progress& progress) {
    ProgressStage stage(progress, "renormalize level set");
    return rebuildAt(grid, 0.0, exteriorHalfWidthVoxels, interiorHalfWidthVoxels, progress);
}

openvdb::FloatGrid::Ptr offsetLevelSet(const openvdb::FloatGrid& grid, double distanceMm, double halfWidthVoxels,
                                       Progress& progress) {
    if (!std::isfinite(distanceMm)) throw Error("offsetLevelSet: non-finite distance");
    ProgressStage stage(progress, "offset level set");
    const double voxel = uniformVoxelSizeMm(grid);
    const double band = bandHalfWidthMm(grid);
    // The iso-surface {phi = d} must lie strictly inside the band, with a voxel to spare for the
    // polygoniser; otherwise widen the band on that side first.
    const double needVoxels = std::abs(distanceMm) / voxel + 2.0;
    if (band / voxel >= needVoxels) {
        // levelSetRebuild's band widths are measured from the new surface.
        return rebuildAt(grid, distanceMm, halfWidthVoxels, halfWidthVoxels, progress);
    }
    const double ex = distanceMm > 0 ? needVoxels : 1.0 + band / voxel;
    const double in = distanceMm < 0 ? needVoxels : 1.0 + band / voxel;
    const auto wide = rebuildAt(grid, 0.0, std::max(ex, 3.0), std::max(in, 3.0), progress);
    return rebuildAt(*wide, distanceMm, halfWidthVoxels, halfWidthVoxels, progress);
}

openvdb::FloatGrid::Ptr closeLevelSet(const openvdb::FloatGrid& grid, double radiusMm, double halfWidthVoxels,
                                      Progress& progress) {
    if (!(radiusMm >= 0)) throw Error("closeLevelSet: negative radius");
    const double voxel = uniformVoxelSizeMm(grid);
    const double mid = std::max(halfWidthVoxels, radiusMm / voxel + 2.0);
    const auto dilated = offsetLevelSet(grid, radiusMm, mid, progress);
    return offsetLevelSet(*dilated, -radiusMm, halfWidthVoxels, progress);
}

openvdb::FloatGrid::Ptr openLevelSet(const openvdb::FloatGrid& grid, double radiusMm, double halfWidthVoxels,
                                     Progress& progress) {
    if (!(radiusMm >= 0)) throw Error("openLevelSet: negative radius");
    const double voxel = uniformVoxelSizeMm(grid);
    const double mid = std::max(halfWidthVoxels, radiusMm / voxel + 2.0);
    const auto eroded = offsetLevelSet(grid, -radiusMm, mid, progress);
    return offsetLevelSet(*eroded, radiusMm, halfWidthVoxels, progress);
}

}  // namespace jawmesh
