// The block partition and the passes of the simplification (SimplifyPasses.h).
#include "filters/SimplifyPasses.h"

#include "filters/BlockSimplifier.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>

namespace jawmesh::simplify {
namespace {

using Cell = std::array<int, 3>;

/// The cells met, in cell order (x, then y, then z: deterministic), searched by bisection in one
/// small array: a map's lookups, 26 per triangle near a block's border (most of them: the margin
/// is most of a block), were a second of serial time per pass on the shared mandible.
struct CellIndex {
    std::vector<Cell> cells;  ///< sorted, unique; block b is cells[b]
    std::int32_t find(const Cell& c) const {
        const auto it = std::lower_bound(cells.begin(), cells.end(), c);
        return it != cells.end() && *it == c ? std::int32_t(it - cells.begin()) : -1;
    }
};

/// The block cell of every triangle (by centroid) and the index of the cells met.
CellIndex cellsOfTriangles(const State& st, double blockMm, double offsetMm, std::vector<Cell>& cellOf) {
    const auto& P = *st.points;
    const std::size_t nt = st.tris.size();
    cellOf.resize(nt);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            const Tri& f = st.tris[t];
            const Vec3 c = (P[std::size_t(f[0])] + P[std::size_t(f[1])] + P[std::size_t(f[2])]) / 3.0;
            for (int k = 0; k < 3; ++k) cellOf[t][std::size_t(k)] = int(std::floor((c[k] - offsetMm) / blockMm));
        }
    });
    CellIndex index;
    index.cells = cellOf;
    tbb::parallel_sort(index.cells.begin(), index.cells.end());
    index.cells.erase(std::unique(index.cells.begin(), index.cells.end()), index.cells.end());
    return index;
}

/// The blocks, other than its own cell's, whose cell triangle t's box (`box`, in cell c) comes
/// within marginMm of, in neighbour order.
void obstacleBlocks(const BBox& box, const Cell& c, const CellIndex& index, double blockMm, double offsetMm,
                    double marginMm, std::vector<std::int32_t>& out) {
    out.clear();
    // Per axis, which neighbours (-1, +1) the box comes near; most triangles sit inside their
    // cell and skip the 26 lookups (the test below then decides exactly, as before).
    bool reach[3][2];
    for (int k = 0; k < 3; ++k) {
        reach[k][0] = box.min[k] <= c[std::size_t(k)] * blockMm + offsetMm + marginMm;
        reach[k][1] = box.max[k] >= (c[std::size_t(k)] + 1) * blockMm + offsetMm - marginMm;
    }
    if (!(reach[0][0] || reach[0][1] || reach[1][0] || reach[1][1] || reach[2][0] || reach[2][1])) return;
    const auto skip = [&](int k, int d) { return d != 0 && !reach[k][d > 0 ? 1 : 0]; };
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                if (!dx && !dy && !dz) continue;
                if (skip(0, dx) || skip(1, dy) || skip(2, dz)) continue;
                const Cell nb{c[0] + dx, c[1] + dy, c[2] + dz};
                const std::int32_t b = index.find(nb);
                if (b < 0) continue;
                bool near = true;
                for (int k = 0; k < 3 && near; ++k) {
                    const double lo = nb[std::size_t(k)] * blockMm + offsetMm - marginMm;
                    const double hi = (nb[std::size_t(k)] + 1) * blockMm + offsetMm + marginMm;
                    near = box.max[k] >= lo && box.min[k] <= hi;
                }
                if (near) out.push_back(b);
            }
}

/// The triangles of `st` that are in none of `blocks`, in order.
std::vector<std::int32_t> trianglesOutside(const State& st, const std::vector<Block>& blocks) {
    std::vector<char> in(st.tris.size(), 0);
    for (const Block& b : blocks)
        for (std::int32_t t : b.tris) in[std::size_t(t)] = 1;
    std::vector<std::int32_t> out;
    for (std::size_t t = 0; t < in.size(); ++t)
        if (!in[t]) out.push_back(std::int32_t(t));
    return out;
}

/// One pass over `blocks` (border: their shared vertices): every block simplified in parallel
/// (blocks only write their own data), then the triangles in no block and the blocks' results put
/// back in that order.
std::size_t runPass(State& st, const std::vector<Block>& blocks, const std::vector<char>& border,
                    const SimplifyOptions& o, Progress& progress, ProgressStage& stage, double from, double to) {
    std::vector<BlockResult> results(blocks.size());
    std::atomic<std::size_t> done{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 1), [&](const auto& r) {
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
            progress.checkCancelled();
            BlockSimplifier s(st, blocks[b], border, o);
            s.run(progress);
            results[b] = s.result();
            const std::size_t d = ++done;
            if (tbb::this_task_arena::current_thread_index() == 0)
                stage.update(from + (to - from) * double(d) / double(blocks.size()));
        }
    });
    State next;
    for (std::int32_t t : trianglesOutside(st, blocks)) {
        next.tris.push_back(st.tris[std::size_t(t)]);
        next.sides.push_back(st.sides[std::size_t(t)]);
        next.pts.push_back(std::move(st.pts[std::size_t(t)]));
    }
    std::size_t collapses = 0;
    for (BlockResult& r : results) {
        next.tris.insert(next.tris.end(), r.tris.begin(), r.tris.end());
        next.sides.insert(next.sides.end(), r.sides.begin(), r.sides.end());
        for (auto& p : r.pts) next.pts.push_back(std::move(p));
        for (std::uint64_t key : r.takenCurves) st.curvePts.erase(key);
        for (auto& [key, pts] : r.curves) st.curvePts[key] = std::move(pts);
        for (std::int32_t v : r.touchedFrozen) st.settled[std::size_t(v)] = 0;
        collapses += r.collapses;
    }
    st.tris = std::move(next.tris);
    st.sides = std::move(next.sides);
    st.pts = std::move(next.pts);
    return collapses;
}

}  // namespace

std::vector<Block> makeBlocks(const State& st, double blockMm, double offsetMm, double marginMm,
                              std::vector<char>& border) {
    const std::size_t nt = st.tris.size();
    border.assign(st.points->size(), 0);
    if (blockMm <= 0) {
        Block all;
        all.tris.resize(nt);
        for (std::size_t t = 0; t < nt; ++t) all.tris[t] = std::int32_t(t);
        return {all};
    }
    const auto& P = *st.points;
    std::vector<Cell> cellOf;
    const CellIndex index = cellsOfTriangles(st, blockMm, offsetMm, cellOf);
    std::vector<Block> blocks(index.cells.size());
    std::vector<std::int32_t> owner(P.size(), -1);
    for (std::size_t t = 0; t < nt; ++t) {
        const std::size_t b = std::size_t(index.find(cellOf[t]));
        blocks[b].tris.push_back(std::int32_t(t));
        for (std::int32_t v : st.tris[t]) {
            if (owner[std::size_t(v)] < 0) owner[std::size_t(v)] = std::int32_t(b);
            else if (owner[std::size_t(v)] != std::int32_t(b)) border[std::size_t(v)] = 1;
        }
    }
    // Each triangle's neighbouring blocks found in parallel, then appended in triangle order.
    std::vector<std::vector<std::int32_t>> near(nt);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<std::int32_t> found;
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            BBox box;
            for (std::int32_t v : st.tris[t]) box.extend(P[std::size_t(v)]);
            obstacleBlocks(box, cellOf[t], index, blockMm, offsetMm, marginMm, found);
            near[t] = found;
        }
    });
    for (std::size_t t = 0; t < nt; ++t)
        for (std::int32_t b : near[t]) blocks[std::size_t(b)].obstacles.push_back(std::int32_t(t));
    return blocks;
}

std::vector<Block> unsettledBlock(const State& st, std::vector<char>& border) {
    const std::size_t nv = st.points->size();
    // the vertices that may still collapse, then their neighbours: a collapse's both ends need
    // their whole star in the block
    std::vector<char> near(nv, 0), inBlock(st.tris.size(), 0);
    for (int ring = 0; ring < 2; ++ring) {
        std::vector<char> grown = near;
        for (const Tri& f : st.tris) {
            bool hit = false;
            for (std::int32_t v : f) hit = hit || (ring == 0 ? !st.settled[std::size_t(v)] : near[std::size_t(v)]);
            if (hit)
                for (std::int32_t v : f) grown[std::size_t(v)] = 1;
        }
        near = std::move(grown);
    }
    Block block;
    border.assign(nv, 0);
    for (std::size_t t = 0; t < st.tris.size(); ++t) {
        const Tri& f = st.tris[t];
        inBlock[t] = near[std::size_t(f[0])] || near[std::size_t(f[1])] || near[std::size_t(f[2])];
        if (inBlock[t]) block.tris.push_back(std::int32_t(t));
    }
    for (std::size_t t = 0; t < st.tris.size(); ++t)
        if (!inBlock[t])
            for (std::int32_t v : st.tris[t]) border[std::size_t(v)] = 1;
    return {block};
}

std::size_t simplifyInPasses(State& st, const SimplifyOptions& o, Progress& progress, ProgressStage& stage) {
    std::size_t collapses = 0;
    std::vector<char> border;
    const double margin = 2.0 * std::max({o.boneMaxEdgeMm, o.toothMaxEdgeMm, o.pdlMaxEdgeMm});
    if (o.blockMm > 0) {
        collapses += runPass(st, makeBlocks(st, o.blockMm, 0.0, margin, border), border, o, progress, stage, 0.0, 0.6);
        collapses += runPass(st, makeBlocks(st, o.blockMm, 0.5 * o.blockMm, margin, border), border, o, progress,
                             stage, 0.6, 0.8);
        // the second pass's borders inside, so the serial pass is left little
        collapses += runPass(st, makeBlocks(st, o.blockMm, 0.25 * o.blockMm, margin, border), border, o, progress,
                             stage, 0.8, 0.9);
    }
    // The last pass: serial, over what may still collapse (everything when the exhaustive
    // intersection test needs every triangle in its grid).
    const std::vector<Block> last = o.blockMm > 0 && !o.exhaustiveIntersectionChecks
                                        ? unsettledBlock(st, border)
                                        : makeBlocks(st, 0.0, 0.0, margin, border);
    collapses += runPass(st, last, border, o, progress, stage, 0.9, 0.97);
    return collapses;
}

}  // namespace jawmesh::simplify
