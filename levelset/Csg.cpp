// Implements levelset/Csg.h; what it computes, its rules and its contract are documented there.
#include "levelset/Csg.h"

#include "io/Error.h"
#include "levelset/ClosestPoints.h"

#include <openvdb/tools/ChangeBackground.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/Morphology.h>
#include <openvdb/tools/LevelSetRebuild.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

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

openvdb::FloatGrid::Ptr withExteriorReach(const openvdb::FloatGrid& grid, double reachMm) {
    const double voxel = uniformVoxelSizeMm(grid);
    const double band = bandHalfWidthMm(grid);
    auto out = grid.deepCopy();
    if (reachMm <= band) return out;
    openvdb::MaskTree region(grid.tree(), false, openvdb::TopologyCopy());
    openvdb::tools::dilateActiveValues(region, int(std::ceil((reachMm - band) / voxel)) + 1,
                                       openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::IGNORE_TILES);
    const auto far = extendExteriorDistance(grid, region, reachMm);
    openvdb::tools::changeLevelSetBackground(out->tree(), float(reachMm));
    auto acc = out->getAccessor();
    for (auto it = far->tree().cbeginValueOn(); it; ++it) acc.setValue(it.getCoord(), *it);
    return out;
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

/// OpenVDB's mesh -> volume (inside levelSetRebuild) is exact within 2 voxels of the surface
/// (errors ~0.03 voxel) but up to ~0.5 voxel off farther out (its narrow-band expansion reuses
/// neighbours' closest primitives). Values beyond 2 voxels are recomputed by closest-point
/// propagation from the accurate inner layers, on each side. The two sides may have different
/// widths (the background is the exterior one), so nothing is clamped: the band keeps its extent.
void repairFarBand(openvdb::FloatGrid& g) {
    const double voxel = uniformVoxelSizeMm(g);
    const double inner = 2.0 * voxel * 1.0001;
    const openvdb::MaskTree band(g.tree(), false, openvdb::TopologyCopy());
    double maxAbs = 0;
    for (auto it = g.tree().cbeginValueOn(); it; ++it) maxAbs = std::max(maxAbs, std::abs(double(*it)));
    if (maxAbs <= inner) return;
    for (int side : {+1, -1}) {
        const auto fixed = propagateClosestPoints(g, band, maxAbs + voxel, -inner, inner, side, true);
        auto acc = g.getAccessor();
        for (auto it = fixed->tree().cbeginValueOn(); it; ++it)
            if (std::abs(*it) > inner && acc.isValueOn(it.getCoord())) acc.setValueOnly(it.getCoord(), *it);
    }
}

openvdb::FloatGrid::Ptr rebuildAt(const openvdb::FloatGrid& grid, double isoMm, double exVoxels, double inVoxels,
                                  Progress& progress) {
    uniformVoxelSizeMm(grid);
    bandHalfWidthMm(grid);
    if (!(exVoxels >= 1.0) || !(inVoxels >= 1.0)) throw Error("level set band half width must be >= 1 voxel");
    Interrupter interrupter(progress);
    openvdb::FloatGrid::Ptr out;
    try {
        // Through the base class: OpenVDB's library holds this instantiation (its interrupter is
        // virtual), so the compiler does not build a mesher of its own here (80 s of the build).
        out = openvdb::tools::levelSetRebuild(grid, float(isoMm), float(exVoxels), float(inVoxels), nullptr,
                                              static_cast<openvdb::util::NullInterrupter*>(&interrupter));
    } catch (const openvdb::Exception& e) {
        throw Error("level set '" + grid.getName() + "': rebuild failed: " + e.what());
    }
    progress.checkCancelled();
    repairFarBand(*out);
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

openvdb::FloatGrid::Ptr extendExteriorDistance(const openvdb::FloatGrid& grid, const openvdb::MaskTree& region,
                                               double maxDistanceMm) {
    const double voxel = uniformVoxelSizeMm(grid);
    const double bg = bandHalfWidthMm(grid);
    // Seeds: the outermost reliable shell of the band (central differences stay inside the band).
    return propagateClosestPoints(grid, region, maxDistanceMm, bg - 2.0001 * voxel, bg - 1.0001 * voxel, +1, false);
}

openvdb::FloatGrid::Ptr extendInteriorDistance(const openvdb::FloatGrid& grid, const openvdb::MaskTree& region,
                                               double maxDistanceMm) {
    const double voxel = uniformVoxelSizeMm(grid);
    const double bg = bandHalfWidthMm(grid);
    return propagateClosestPoints(grid, region, maxDistanceMm, bg - 2.0001 * voxel, bg - 1.0001 * voxel, -1, false);
}

}  // namespace jawmesh
