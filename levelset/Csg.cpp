// Implements levelset/Csg.h; what it computes, its rules and its contract are documented there.
#include "levelset/Csg.h"

#include "io/Error.h"

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
openvdb::FloatGrid::Ptr propagateClosestPoints(const openvdb::FloatGrid& grid, const openvdb::MaskTree& region,
                                               double maxDistanceMm, double seedLowMm, double seedHighMm, int side,
                                               bool withBand);

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

namespace {
/// The queue of closest-point propagation: pops offers by squared distance, ties by coordinate.
/// Each voxel's offers have strictly falling distances, so that order is total and the pops are
/// the same as a single binary heap's; but a heap of millions of offers spends most of its time
/// in cache misses, so offers wait in buckets of distance and only the current bucket is a heap.
class OfferQueue {
public:
    struct Item {
        float d2;  ///< squared distance, voxels^2
        openvdb::Coord c;
        openvdb::Vec3s cp;  ///< closest point offered, index space
        bool operator>(const Item& o) const { return d2 != o.d2 ? d2 > o.d2 : o.c < c; }
    };
    explicit OfferQueue(double maxD2) : buckets_(std::size_t(std::max(0.0, maxD2) / kWidth) + 2) {}
    bool empty() const { return heap_.empty() && size_ == 0; }
    void push(const Item& it) {
        const std::size_t b = bucketOf(it.d2);
        if (b <= current_) {  // at or below what is being popped: the heap takes it
            heap_.push_back(it);
            std::push_heap(heap_.begin(), heap_.end(), std::greater<Item>());
            return;
        }
        buckets_[b].push_back(it);
        ++size_;
    }
    Item pop() {
        while (heap_.empty()) {  // the next bucket with offers becomes the heap
            ++current_;
            std::swap(heap_, buckets_[current_]);
            size_ -= heap_.size();
            std::make_heap(heap_.begin(), heap_.end(), std::greater<Item>());
        }
        std::pop_heap(heap_.begin(), heap_.end(), std::greater<Item>());
        const Item it = heap_.back();
        heap_.pop_back();
        return it;
    }

private:
    static constexpr double kWidth = 0.25;  ///< voxels^2 per bucket
    std::size_t bucketOf(float d2) const { return std::min(buckets_.size() - 1, std::size_t(double(d2) / kWidth)); }
    std::vector<std::vector<Item>> buckets_;
    std::vector<Item> heap_;
    std::size_t current_ = 0, size_ = 0;
};

/// Closest-point propagation (see extendExteriorDistance) on the side `side` (+1 outside, -1
/// inside) of grid, seeded by the band voxels with seedLowMm <= side * value <= seedHighMm, into
/// region voxels with side * value > max(seedLowMm, 0); writes side * distance for voxels off the
/// band, and for band voxels too when withBand. A thin seed shell is several times cheaper than
/// the whole band (every path leaving the band crosses it) but less accurate near the shell
/// (~0.25 voxel instead of ~0.12: the lattice samples the closest points more sparsely).
openvdb::FloatGrid::Ptr propagateClosestPoints(const openvdb::FloatGrid& grid, const openvdb::MaskTree& region,
                                               double maxDistanceMm, double seedLowMm, double seedHighMm, int side,
                                               bool withBand) {
    using openvdb::Coord;
    using openvdb::Vec3d;
    using openvdb::Vec3s;
    const double voxel = uniformVoxelSizeMm(grid);
    const float sideF = float(side);
    const double maxIdx = maxDistanceMm / voxel, max2 = maxIdx * maxIdx;
    auto out = openvdb::FloatGrid::create(float(maxDistanceMm));
    out->setTransform(grid.transform().copy());
    if (!(maxDistanceMm > 0)) return out;

    std::vector<Coord> nbr;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz)
                if (dx || dy || dz) nbr.emplace_back(dx, dy, dz);

    // Dijkstra-like order: a voxel is settled when it is the nearest one left in the queue, taking
    // the closest point it was offered by its settled neighbours. Ties break by coordinate, so the
    // result is deterministic. (Settling layer by layer instead errs by over half a voxel at 6
    // voxels from a sphere.)
    OfferQueue queue(max2);
    openvdb::FloatTree offered(std::numeric_limits<float>::max());
    openvdb::MaskTree settled(false);
    openvdb::tree::ValueAccessor<openvdb::FloatTree> offAcc(offered);
    openvdb::tree::ValueAccessor<openvdb::MaskTree> doneAcc(settled);
    openvdb::tree::ValueAccessor<const openvdb::MaskTree> ra(region);
    auto ga = grid.getConstAccessor();
    const double seedLimit = seedHighMm, seedLow = seedLowMm;
    const float outward = float(std::max(seedLowMm, 0.0));
    for (auto leaf = region.cbeginLeaf(); leaf; ++leaf) {
        const auto* gl = grid.tree().probeConstLeaf(leaf->origin());
        if (!gl) continue;
        for (auto v = gl->cbeginValueOn(); v; ++v) {
            const double d = *v;
            if (side * d > seedLimit || side * d < seedLow) continue;
            const Coord c = v.getCoord();
            const Vec3d g(ga.getValue(c.offsetBy(1, 0, 0)) - ga.getValue(c.offsetBy(-1, 0, 0)),
                          ga.getValue(c.offsetBy(0, 1, 0)) - ga.getValue(c.offsetBy(0, -1, 0)),
                          ga.getValue(c.offsetBy(0, 0, 1)) - ga.getValue(c.offsetBy(0, 0, -1)));
            const double len = g.length();
            if (!(len > 1e-6 * voxel)) continue;
            const Vec3d p = c.asVec3d() - (d / voxel) * (g / len);
            const float d2 = float((d / voxel) * (d / voxel));
            offAcc.setValue(c, d2);
            queue.push({d2, c, Vec3s(p)});
        }
    }
    auto outAcc = out->getAccessor();
    while (!queue.empty()) {
        const OfferQueue::Item it = queue.pop();
        if (doneAcc.isValueOn(it.c)) continue;
        doneAcc.setValueOn(it.c);
        if (withBand || !ga.isValueOn(it.c)) outAcc.setValue(it.c, sideF * float(std::sqrt(double(it.d2)) * voxel));
        const Vec3d p(it.cp);
        for (const Coord& o : nbr) {
            const Coord q = it.c + o;
            if (doneAcc.isValueOn(q) || !ra.isValueOn(q) || !(sideF * ga.getValue(q) > outward)) continue;
            const float d2 = float((q.asVec3d() - p).lengthSqr());
            if (!(d2 <= max2) || !(d2 < offAcc.getValue(q))) continue;
            offAcc.setValue(q, d2);
            queue.push({d2, q, it.cp});
        }
    }
    out->setGridClass(openvdb::GRID_LEVEL_SET);
    return out;
}

}  // namespace

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
