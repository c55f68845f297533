// Implements filters/LabelEdges.h; what it computes, its rules and its contract are documented there.
#include "filters/LabelEdges.h"

#include <tbb/parallel_for.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_sort.h>

#include <algorithm>

namespace jawmesh {
namespace {

using MaskTree = openvdb::MaskTree;

/// Adds to `mask` the voxels of every tile face of `labels` across which the label changes into
/// another tile or the background (a change next to a leaf is seen from the leaf's voxels).
/// Nothing else visits such a change: a level set whose sign jumps between inactive values (winding
/// numbers closing a hole in the input surface, or deciding inside where overlapping shells leave
/// no triangle) has one, and a missed change is a hole in the extracted surface.
void addTileFacesWithLabelChanges(const openvdb::Int32Grid& labels, MaskTree& mask) {
    using Leaf = openvdb::Int32Tree::LeafNodeType;
    constexpr int kBlock = int(Leaf::DIM);  // tiles are unions of whole leaf-sized blocks
    auto acc = labels.getConstAccessor();
    openvdb::tree::ValueAccessor<MaskTree> maskAcc(mask);
    for (auto it = labels.tree().cbeginValueAll(); it; ++it) {
        if (!it.isTileValue() || *it == labels.background()) continue;  // background tiles: seen from the other side
        const openvdb::CoordBBox box = it.getBoundingBox();
        for (int axis = 0; axis < 3; ++axis) {
            const int d1 = (axis + 1) % 3, d2 = (axis + 2) % 3;
            for (const int side : {-1, 1}) {
                openvdb::Coord face = box.min();
                face[axis] = side > 0 ? box.max()[axis] : box.min()[axis];
                for (int b1 = box.min()[d1]; b1 <= box.max()[d1]; b1 += kBlock)
                    for (int b2 = box.min()[d2]; b2 <= box.max()[d2]; b2 += kBlock) {
                        openvdb::Coord across = face;
                        across[axis] += side;
                        across[d1] = b1;
                        across[d2] = b2;
                        if (acc.probeConstLeaf(across) || acc.getValue(across) == *it) continue;
                        for (int i = 0; i < kBlock; ++i)
                            for (int j = 0; j < kBlock; ++j) {
                                openvdb::Coord v = face;
                                v[d1] = b1 + i;
                                v[d2] = b2 + j;
                                maskAcc.setValueOn(v);
                            }
                    }
            }
        }
    }
}

/// The label edges that the mask leaf's voxels own (findLabelEdges). Neighbours inside the leaf are
/// read from the label leaf's buffer (or its tile's value), others through the accessors: six
/// accessor reads per voxel were a twentieth of the extraction.
void edgesOfLeaf(const MaskTree::LeafNodeType& maskLeaf, const openvdb::Int32Grid::ConstAccessor& acc,
                 const openvdb::tree::ValueAccessor<const MaskTree>& maskAcc, std::vector<LabelEdge>& out) {
    using Leaf = openvdb::Int32Tree::LeafNodeType;
    constexpr int kDim = int(Leaf::DIM);
    const Leaf* leaf = acc.probeConstLeaf(maskLeaf.origin());
    const Label tile = leaf ? 0 : acc.getValue(maskLeaf.origin());
    const auto local = [&](openvdb::Index offset) { return leaf ? leaf->getValue(offset) : tile; };
    for (auto it = maskLeaf.cbeginValueOn(); it; ++it) {
        const openvdb::Coord v = it.getCoord();
        const openvdb::Index n = it.pos();
        const Label lv = local(n);
        for (int axis = 0; axis < 3; ++axis) {
            // offsets in a leaf: x is the slowest axis (stride DIM^2), z the fastest
            const openvdb::Index stride = openvdb::Index(1) << (Leaf::LOG2DIM * openvdb::Index(2 - axis));
            const int at = v[axis] - maskLeaf.origin()[axis];
            openvdb::Coord w = v;
            w[axis] += 1;
            if ((at + 1 < kDim ? local(n + stride) : acc.getValue(w)) != lv) out.push_back({v, axis});
            openvdb::Coord u = v;
            u[axis] -= 1;
            // edge (u, v) belongs to u when u is visited itself
            const bool uVisited = at > 0 ? maskLeaf.isValueOn(n - stride) : maskAcc.isValueOn(u);
            if (!uVisited && (at > 0 ? local(n - stride) : acc.getValue(u)) != lv) out.push_back({u, axis});
        }
    }
}

}  // namespace

std::vector<LabelEdge> findLabelEdges(const openvdb::Int32Grid& labels) {
    MaskTree mask;
    for (auto leaf = labels.tree().cbeginLeaf(); leaf; ++leaf)
        mask.touchLeaf(leaf->origin())->setValuesOn();
    addTileFacesWithLabelChanges(labels, mask);
    mask.voxelizeActiveTiles();

    std::vector<const MaskTree::LeafNodeType*> leaves;
    leaves.reserve(mask.leafCount());
    for (auto leaf = mask.cbeginLeaf(); leaf; ++leaf) leaves.push_back(leaf.getLeaf());

    std::vector<std::vector<LabelEdge>> perLeaf(leaves.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 16), [&](const auto& r) {
        auto acc = labels.getConstAccessor();
        openvdb::tree::ValueAccessor<const MaskTree> maskAcc(mask);
        for (std::size_t i = r.begin(); i != r.end(); ++i) edgesOfLeaf(*leaves[i], acc, maskAcc, perLeaf[i]);
    });
    std::vector<LabelEdge> edges;
    std::size_t total = 0;
    for (const auto& e : perLeaf) total += e.size();
    edges.reserve(total);
    for (const auto& e : perLeaf) edges.insert(edges.end(), e.begin(), e.end());
    tbb::parallel_sort(edges.begin(), edges.end(), [](const LabelEdge& a, const LabelEdge& b) {
        return a.voxel < b.voxel || (a.voxel == b.voxel && a.axis < b.axis);
    });
    return edges;
}

void updateLabelEdges(std::vector<LabelEdge>& edges, const openvdb::Int32Grid& labels,
                      const std::vector<openvdb::Coord>& changed) {
    if (changed.empty()) return;
    const auto before = [](const LabelEdge& a, const LabelEdge& b) {
        return a.voxel < b.voxel || (a.voxel == b.voxel && a.axis < b.axis);
    };
    const auto same = [](const LabelEdge& a, const LabelEdge& b) { return a.voxel == b.voxel && a.axis == b.axis; };
    std::vector<LabelEdge> recheck;  // the six edges at every changed voxel
    recheck.reserve(6 * changed.size());
    for (const openvdb::Coord& v : changed)
        for (int axis = 0; axis < 3; ++axis) {
            openvdb::Coord u = v;
            u[axis] -= 1;
            recheck.push_back({v, axis});
            recheck.push_back({u, axis});
        }
    std::sort(recheck.begin(), recheck.end(), before);
    recheck.erase(std::unique(recheck.begin(), recheck.end(), same), recheck.end());
    // in place (the edges are a few hundred megabytes on a jaw), by one merge of the two sorted lists
    std::size_t kept = 0;
    auto r = recheck.begin();
    for (const LabelEdge& e : edges) {
        while (r != recheck.end() && before(*r, e)) ++r;
        if (r == recheck.end() || !same(*r, e)) edges[kept++] = e;
    }
    edges.resize(kept);
    auto acc = labels.getConstAccessor();
    std::vector<LabelEdge> changes;
    for (const LabelEdge& e : recheck) {
        openvdb::Coord w = e.voxel;
        w[e.axis] += 1;
        if (acc.getValue(e.voxel) != acc.getValue(w)) changes.push_back(e);
    }
    // merged from the back, so no copy of the edges is made
    std::size_t added = changes.size();
    edges.resize(kept + added);
    for (std::size_t out = kept + added; added > 0; --out) {
        if (kept > 0 && before(changes[added - 1], edges[kept - 1])) edges[out - 1] = edges[--kept];
        else edges[out - 1] = changes[--added];
    }
}

namespace {

using MaskLeaf = MaskTree::LeafNodeType;

/// Writes the voxels of leaves [first, last) (one origin x, sorted by origin) at `out` in order.
void writeSlab(const MaskLeaf* const* first, const MaskLeaf* const* last, openvdb::Coord* out) {
    for (int dx = 0; dx < int(MaskLeaf::DIM); ++dx)
        for (const MaskLeaf* const* row = first; row < last;) {  // leaves of one origin y
            const MaskLeaf* const* end = row;
            while (end < last && (*end)->origin().y() == (*row)->origin().y()) ++end;
            for (int dy = 0; dy < int(MaskLeaf::DIM); ++dy)
                for (const MaskLeaf* const* leaf = row; leaf < end; ++leaf) {
                    // word dx of the mask holds the plane, byte dy its z row
                    const auto word = (*leaf)->getValueMask().template getWord<openvdb::Index64>(openvdb::Index(dx));
                    for (unsigned zs = unsigned(word >> (8 * dy)) & 0xffu; zs; zs &= zs - 1)
                        *out++ = (*leaf)->origin().offsetBy(dx, dy, __builtin_ctz(zs));
                }
            row = end;
        }
}

/// The active voxels of a mask in (x, y, z) order without a sort of the voxels: the leaves are
/// sorted by origin (y and z before x would not do: rows of leaves interleave), then each plane
/// x = const of a row of leaves (same origin x and y) is read leaf by leaf, one y at a time (a
/// leaf's offset is 64 x + 8 y + z, so the bits of a plane are one word and of a row one byte).
std::vector<openvdb::Coord> sortedVoxels(const MaskTree& mask) {
    std::vector<const MaskLeaf*> leaves;
    for (auto leaf = mask.cbeginLeaf(); leaf; ++leaf) leaves.push_back(leaf.getLeaf());
    tbb::parallel_sort(leaves.begin(), leaves.end(), [](const MaskLeaf* a, const MaskLeaf* b) { return a->origin() < b->origin(); });
    // rows: leaves of one origin x (a slab of 8 planes), each slab filled by one task
    std::vector<std::size_t> slab(1, 0), start(1, 0);
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        if (i > 0 && leaves[i]->origin().x() != leaves[i - 1]->origin().x()) slab.push_back(i);
        start.push_back(start.back() + leaves[i]->onVoxelCount());
    }
    slab.push_back(leaves.size());
    std::vector<openvdb::Coord> cells(start.back());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, slab.size() - 1), [&](const auto& r) {
        for (std::size_t k = r.begin(); k != r.end(); ++k)
            writeSlab(leaves.data() + slab[k], leaves.data() + slab[k + 1], cells.data() + start[slab[k]]);
    });
    return cells;
}

}  // namespace

std::vector<openvdb::Coord> dualCellsOf(const std::vector<LabelEdge>& edges) {
    // Each edge's four cells are marked in a mask (one per thread, then united: the same set
    // whatever the threads), read out in order (sortedVoxels). Sorting the four copies of every
    // cell instead took 1.3 GB and about a tenth of the extraction on the shared mandible.
    tbb::enumerable_thread_specific<MaskTree> masks;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, edges.size(), 1 << 16), [&](const auto& r) {
        openvdb::tree::ValueAccessor<MaskTree> acc(masks.local());
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const int d1 = (edges[i].axis + 1) % 3, d2 = (edges[i].axis + 2) % 3;
            for (int k = 0; k < 4; ++k) {
                openvdb::Coord c = edges[i].voxel;
                c[d1] -= (k & 1);
                c[d2] -= (k >> 1);
                acc.setValueOn(c);
            }
        }
    });
    MaskTree all;
    for (MaskTree& m : masks) all.topologyUnion(m);
    masks.clear();
    return sortedVoxels(all);
}

std::int64_t dualCellIndex(const std::vector<openvdb::Coord>& cells, const openvdb::Coord& c, std::size_t& hint) {
    // Bracket c between lo and hi (cells[lo] < c <= cells[hi], ends as -1 and n) by doubling steps
    // from the hint, then the usual lower bound inside the bracket.
    const std::size_t n = cells.size();
    std::size_t lo = 0, hi = n;
    std::size_t at = std::min(hint, n == 0 ? 0 : n - 1);
    if (n > 0 && cells[at] < c) {
        std::size_t step = 1;
        lo = at;
        while (lo + step < n && cells[lo + step] < c) {
            lo += step;
            step *= 2;
        }
        hi = std::min(n, lo + step);
        ++lo;  // cells[lo - 1] < c
    } else if (n > 0) {
        std::size_t step = 1;
        hi = at;  // c <= cells[hi]
        while (hi >= step && !(cells[hi - step] < c)) {
            hi -= step;
            step *= 2;
        }
        lo = hi >= step ? hi - step + 1 : 0;
    }
    const auto it = std::lower_bound(cells.begin() + std::ptrdiff_t(lo), cells.begin() + std::ptrdiff_t(hi), c);
    hint = std::size_t(it - cells.begin());
    return (it != cells.end() && *it == c) ? std::int64_t(hint) : -1;
}

}  // namespace jawmesh
