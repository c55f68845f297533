// Implements filters/DualQuads.h; what it computes, its rules and its contract are documented there.
#include "filters/DualQuads.h"

#include <tbb/parallel_for.h>

namespace jawmesh {

std::vector<DualQuad> dualQuadsOf(const std::vector<LabelEdge>& edges, const std::vector<openvdb::Coord>& cells,
                                  const openvdb::Int32Grid& labels, bool mirrored) {
    std::vector<DualQuad> quads(edges.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, edges.size(), 4096), [&](const auto& r) {
        auto acc = labels.getConstAccessor();
        std::size_t hint[4] = {0, 0, 0, 0};  // each corner's last cell: the edges come sorted
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const LabelEdge& e = edges[i];
            const int d1 = (e.axis + 1) % 3, d2 = (e.axis + 2) % 3;
            openvdb::Coord c[4] = {e.voxel, e.voxel, e.voxel, e.voxel};  // normal along +axis
            c[0][d1] -= 1;
            c[0][d2] -= 1;
            c[1][d2] -= 1;
            c[3][d1] -= 1;
            DualQuad& q = quads[i];
            for (int k = 0; k < 4; ++k) q.cells[std::size_t(k)] = std::int32_t(dualCellIndex(cells, c[k], hint[k]));
            openvdb::Coord w = e.voxel;
            w[e.axis] += 1;
            const Label la = acc.getValue(e.voxel), lb = acc.getValue(w);
            q.sides = {std::min(la, lb), std::max(la, lb)};
            // the quad's normal points into lb; flip so that it points into sides[0]
            if ((lb != q.sides[0]) != mirrored) std::swap(q.cells[1], q.cells[3]);
        }
    });
    return quads;
}

int quadTriangles(std::array<std::int32_t, 4> q, const std::vector<Vec3>& P, Tri out[2]) {
    // drop a corner equal to the one before it (merged cells meet the quad on one side)
    std::array<std::int32_t, 4> d{};
    int n = 0;
    for (int k = 0; k < 4; ++k)
        if (q[std::size_t(k)] != q[std::size_t((k + 3) % 4)]) d[std::size_t(n++)] = q[std::size_t(k)];
    if (n == 0) return 0;  // all four the same vertex
    if (n == 3) {
        out[0] = {d[0], d[1], d[2]};
        return 1;
    }
    if (n != 4) return 0;
    const auto at = [&](int k) -> const Vec3& { return P[std::size_t(d[std::size_t(k)])]; };
    if ((at(0) - at(2)).squaredNorm() <= (at(1) - at(3)).squaredNorm()) {
        out[0] = {d[0], d[1], d[2]};
        out[1] = {d[0], d[2], d[3]};
    } else {
        out[0] = {d[0], d[1], d[3]};
        out[1] = {d[1], d[2], d[3]};
    }
    return 2;
}

void emitQuadTriangles(const std::vector<DualQuad>& quads, const std::vector<std::int32_t>& vertexOf,
                       const std::vector<Vec3>& P, std::vector<Tri>& triangles,
                       std::vector<std::array<Label, 2>>& sides) {
    // Counted per chunk first, then written at the chunk's offset: the order does not depend on
    // the threads.
    constexpr std::size_t kChunk = 65536;
    const std::size_t chunks = (quads.size() + kChunk - 1) / kChunk;
    const auto mapped = [&](const DualQuad& q) {
        std::array<std::int32_t, 4> v;
        for (int k = 0; k < 4; ++k) v[std::size_t(k)] = vertexOf[std::size_t(q.cells[std::size_t(k)])];
        return v;
    };
    std::vector<std::size_t> offset(chunks + 1, 0);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        Tri t[2];
        for (std::size_t i = c * kChunk; i < std::min(quads.size(), (c + 1) * kChunk); ++i)
            offset[c + 1] += std::size_t(quadTriangles(mapped(quads[i]), P, t));
    });
    for (std::size_t c = 0; c < chunks; ++c) offset[c + 1] += offset[c];
    triangles.resize(offset[chunks]);
    sides.resize(offset[chunks]);
    tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t c) {
        std::size_t at = offset[c];
        Tri t[2];
        for (std::size_t i = c * kChunk; i < std::min(quads.size(), (c + 1) * kChunk); ++i) {
            const int n = quadTriangles(mapped(quads[i]), P, t);
            for (int k = 0; k < n; ++k) {
                triangles[at] = t[k];
                sides[at++] = quads[i].sides;
            }
        }
    });
}

}  // namespace jawmesh
