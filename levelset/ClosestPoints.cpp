// Implements levelset/ClosestPoints.h; what it computes, its rules and its contract are documented there.
#include "levelset/ClosestPoints.h"

#include "levelset/Csg.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace jawmesh {
namespace {

using openvdb::Coord;
using MaskLeaf = openvdb::MaskTree::LeafNodeType;
using LeafMask = MaskLeaf::NodeMaskType;

/// The queue: pops offers by squared distance, ties by coordinate. Each voxel's offers have
/// strictly falling distances, so that order is total and the pops are the same as a single binary
/// heap's; but a heap of millions of offers spends most of its time in cache misses, so offers wait
/// in buckets of distance and only the current bucket is a heap.
class OfferQueue {
public:
    struct Item {
        float d2;  ///< squared distance, voxels^2
        Coord c;
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

/// One leaf of the region. offered: the smallest squared distance offered so far (voxels^2,
/// +max when none); once the voxel is settled, minus the distance it took (so the sign bit says
/// settled, -0 included). open: region voxels on the propagating side, which may take offers.
/// band: the grid's active voxels (their values are the grid's own unless withBand). region and
/// grid: the leaves at the origin (grid null where the grid has a tile).
struct Slab {
    Coord origin;
    const MaskLeaf* region = nullptr;
    const openvdb::FloatTree::LeafNodeType* grid = nullptr;
    std::array<float, MaskLeaf::SIZE> offered;
    LeafMask open, band;
};

/// The region's leaves, found by leaf coordinate through a dense table over their bounding box.
class Slabs {
public:
    explicit Slabs(const openvdb::MaskTree& region) {
        Coord lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
        for (auto leaf = region.cbeginLeaf(); leaf; ++leaf) {
            const Coord l = leafCoord(leaf->origin());
            lo.minComponent(l);
            hi.maxComponent(l);
        }
        if (lo.x() > hi.x()) return;
        lo_ = lo;
        dim_ = hi - lo + Coord(1);
        table_.assign(std::size_t(dim_.x()) * std::size_t(dim_.y()) * std::size_t(dim_.z()), -1);
        for (auto leaf = region.cbeginLeaf(); leaf; ++leaf) {
            table_[index(leafCoord(leaf->origin()))] = std::int32_t(slabs_.size());
            slabs_.emplace_back();
            slabs_.back().origin = leaf->origin();
            slabs_.back().region = leaf.getLeaf();
        }
    }
    std::vector<Slab>& all() { return slabs_; }
    /// The slab holding voxel c, or null outside the region's leaves.
    Slab* find(const Coord& c) {
        const Coord l = leafCoord(c) - lo_;
        if (l.x() < 0 || l.y() < 0 || l.z() < 0 || l.x() >= dim_.x() || l.y() >= dim_.y() || l.z() >= dim_.z()) return nullptr;
        const std::int32_t s = table_[index(l + lo_)];
        return s < 0 ? nullptr : &slabs_[std::size_t(s)];
    }

private:
    static Coord leafCoord(const Coord& c) {
        constexpr int log2 = int(MaskLeaf::LOG2DIM);
        return Coord(c.x() >> log2, c.y() >> log2, c.z() >> log2);
    }
    std::size_t index(const Coord& l) const {
        const Coord d = l - lo_;
        return (std::size_t(d.x()) * std::size_t(dim_.y()) + std::size_t(d.y())) * std::size_t(dim_.z()) + std::size_t(d.z());
    }
    Coord lo_, dim_;
    std::vector<std::int32_t> table_;
    std::vector<Slab> slabs_;
};

inline openvdb::Index offsetOf(const Coord& c) { return MaskLeaf::coordToOffset(c); }

/// Fills each slab's masks from its region leaf and the grid (a leaf the grid lacks is one tile value).
void fillSlabs(Slabs& slabs, const openvdb::FloatGrid& grid, float side, float outward) {
    auto ga = grid.getConstAccessor();
    for (Slab& s : slabs.all()) {
        s.offered.fill(std::numeric_limits<float>::max());
        s.grid = grid.tree().probeConstLeaf(s.origin);
        const float tile = s.grid ? 0.0f : ga.getValue(s.origin);
        if (s.grid)
            s.band = s.grid->getValueMask();
        else if (ga.isValueOn(s.origin))
            s.band.setOn();
        for (auto v = s.region->getValueMask().beginOn(); v; ++v) {
            const float g = s.grid ? s.grid->getValue(v.pos()) : tile;
            if (side * g > outward) s.open.setOn(v.pos());
        }
    }
}

/// Offers every seed its own closest point (central differences of the grid).
void seed(Slabs& slabs, const openvdb::FloatGrid& grid, double voxel, double seedLowMm, double seedHighMm, int side,
          OfferQueue& queue) {
    auto ga = grid.getConstAccessor();
    for (Slab& s : slabs.all()) {
        if (!s.grid) continue;
        for (auto v = s.grid->cbeginValueOn(); v; ++v) {
            const double d = *v;
            if (side * d > seedHighMm || side * d < seedLowMm) continue;
            const Coord c = v.getCoord();
            const openvdb::Vec3d g(ga.getValue(c.offsetBy(1, 0, 0)) - ga.getValue(c.offsetBy(-1, 0, 0)),
                                   ga.getValue(c.offsetBy(0, 1, 0)) - ga.getValue(c.offsetBy(0, -1, 0)),
                                   ga.getValue(c.offsetBy(0, 0, 1)) - ga.getValue(c.offsetBy(0, 0, -1)));
            const double len = g.length();
            if (!(len > 1e-6 * voxel)) continue;
            const openvdb::Vec3d p = c.asVec3d() - (d / voxel) * (g / len);
            const float d2 = float((d / voxel) * (d / voxel));
            s.offered[v.pos()] = d2;
            queue.push({d2, c, openvdb::Vec3s(p)});
        }
    }
}

/// Settles voxels nearest first; each offers its closest point to its open, unsettled neighbours.
void settle(Slabs& slabs, double max2, OfferQueue& queue) {
    std::array<Coord, 26> nbr;
    int n = 0;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz)
                if (dx || dy || dz) nbr[std::size_t(n++)] = Coord(dx, dy, dz);
    while (!queue.empty()) {
        const OfferQueue::Item it = queue.pop();
        Slab* home = slabs.find(it.c);
        float& mine = home->offered[offsetOf(it.c)];
        if (std::signbit(mine)) continue;  // settled by a nearer offer
        mine = -it.d2;
        const openvdb::Vec3d p(it.cp);
        for (const Coord& o : nbr) {
            const Coord q = it.c + o;
            constexpr int kOrigin = ~int(MaskLeaf::DIM - 1);  // a voxel's leaf origin: its coordinates & this
            Slab* s = (q.x() & kOrigin) == home->origin.x() && (q.y() & kOrigin) == home->origin.y() &&
                              (q.z() & kOrigin) == home->origin.z()
                          ? home
                          : slabs.find(q);
            if (!s) continue;
            const openvdb::Index i = offsetOf(q);
            if (!s->open.isOn(i)) continue;
            const float d2 = float((q.asVec3d() - p).lengthSqr());
            if (!(d2 <= max2) || !(d2 < s->offered[i])) continue;  // a settled voxel's offer is negative
            s->offered[i] = d2;
            queue.push({d2, q, it.cp});
        }
    }
}

}  // namespace

openvdb::FloatGrid::Ptr propagateClosestPoints(const openvdb::FloatGrid& grid, const openvdb::MaskTree& region,
                                               double maxDistanceMm, double seedLowMm, double seedHighMm, int side,
                                               bool withBand) {
    const double voxel = uniformVoxelSizeMm(grid);
    const double maxIdx = maxDistanceMm / voxel, max2 = maxIdx * maxIdx;
    auto out = openvdb::FloatGrid::create(float(maxDistanceMm));
    out->setTransform(grid.transform().copy());
    if (!(maxDistanceMm > 0)) return out;

    Slabs slabs(region);
    fillSlabs(slabs, grid, float(side), float(std::max(seedLowMm, 0.0)));
    OfferQueue queue(max2);
    seed(slabs, grid, voxel, seedLowMm, seedHighMm, side, queue);
    settle(slabs, max2, queue);

    for (const Slab& s : slabs.all()) {
        openvdb::FloatTree::LeafNodeType* leaf = nullptr;
        for (openvdb::Index i = 0; i < MaskLeaf::SIZE; ++i) {
            const float f = s.offered[i];
            if (!std::signbit(f) || (!withBand && s.band.isOn(i))) continue;
            if (!leaf) leaf = out->tree().touchLeaf(s.origin);
            leaf->setValueOn(i, float(side) * float(std::sqrt(double(-f)) * voxel));
        }
    }
    out->setGridClass(openvdb::GRID_LEVEL_SET);
    return out;
}

}  // namespace jawmesh
