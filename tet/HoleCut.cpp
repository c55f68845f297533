// Implements tet/HoleCut.h; what it computes, its rules and its contract are documented there.
#include "tet/HoleCut.h"

#include "filters/TriangleGeometry.h"
#include "tet/InterfaceTriangleIndex.h"
#include "tet/TetFaceAdjacency.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace jawmesh {
namespace {

Vec3 centroid(const TetMesh& m, std::size_t t) {
    Vec3 c = Vec3::Zero();
    for (const std::int32_t v : m.tets[t]) c += m.nodes[std::size_t(v)];
    return c / 4.0;
}

bool nearAHole(const TetMesh& m, std::size_t t, const std::vector<HoleBall>& holes) {
    for (const HoleBall& h : holes)
        if (std::all_of(m.tets[t].begin(), m.tets[t].end(),
                        [&](std::int32_t v) { return (m.nodes[std::size_t(v)] - h.centre).norm() <= h.radiusMm; }))
            return true;
    return false;
}

std::int32_t findRoot(std::vector<std::int32_t>& parent, std::int32_t x) {
    while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
    return x;
}

}  // namespace

HoleCutPatch holeCutPatch(const InterfaceComplex& complex, const TetMesh& m, const std::vector<std::array<std::int32_t, 3>>& facets,
                          const std::vector<HoleBall>& holes, bool sourcesAtTheirDistance) {
    HoleCutPatch patch;
    const InterfaceTriangleIndex triangleOf = interfaceTriangleIndex(complex);
    const std::size_t nt = m.tets.size();
    const TetFaceAdjacency adj = tetFaceAdjacency(m);
    std::vector<char> near(nt);
    for (std::size_t t = 0; t < nt; ++t) near[t] = nearAHole(m, t, holes) ? 1 : 0;
    // Neighbours across faces that are no surface, and components of the tets away from the holes.
    std::vector<std::vector<std::int32_t>> next(nt);
    std::vector<std::int32_t> parent(nt);
    for (std::size_t t = 0; t < nt; ++t) parent[t] = std::int32_t(t);
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        if (adj.groupSize(g) != 2) continue;
        const TetFaceRef& f0 = adj.faces[std::size_t(adj.groupStart[g])];
        const TetFaceRef& f1 = adj.faces[std::size_t(adj.groupStart[g]) + 1];
        if (triangleOf.contains(f0.key) || std::binary_search(facets.begin(), facets.end(), f0.key)) continue;
        next[std::size_t(f0.tet)].push_back(f1.tet);
        next[std::size_t(f1.tet)].push_back(f0.tet);
        if (near[std::size_t(f0.tet)] || near[std::size_t(f1.tet)]) continue;
        const std::int32_t a = findRoot(parent, f0.tet), b = findRoot(parent, f1.tet);
        if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
    }
    constexpr Label kUnset = -1;
    std::vector<Label> label(nt, kUnset), componentLabel(nt, kUnset);
    std::vector<double> dist(nt, std::numeric_limits<double>::infinity());
    using Item = std::pair<double, std::int32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    for (const TetFaceRef& f : adj.faces) {
        const std::size_t input = triangleOf.find(f.key);
        if (input == InterfaceTriangleIndex::npos) continue;
        // An input triangle wound as the tet's outward face points out of the tet, into sides[0]:
        // the tet is on sides[1].
        const Tri& tri = complex.surface.triangles[input];
        const Label side = complex.sides[input][sameWinding(tri, outwardFace(m.tets[std::size_t(f.tet)], f.local)) ? 1 : 0];
        if (!near[std::size_t(f.tet)]) {
            Label& c = componentLabel[std::size_t(findRoot(parent, f.tet))];
            if (c != kUnset && c != side) {
                patch.local = false;
                return patch;
            }
            c = side;
            continue;
        }
        // A large tet on the rim of a hole can reach through it far into the other region: it
        // starts at its centroid's distance from the triangle.
        const double d = !sourcesAtTheirDistance ? 0.0 : std::sqrt(squaredDistanceToTriangle(centroid(m, std::size_t(f.tet)), complex.surface.vertices[std::size_t(tri[0])],
                                                             complex.surface.vertices[std::size_t(tri[1])], complex.surface.vertices[std::size_t(tri[2])]));
        if (d >= dist[std::size_t(f.tet)]) continue;
        label[std::size_t(f.tet)] = side;
        dist[std::size_t(f.tet)] = d;
        queue.push({d, f.tet});
    }
    for (std::size_t t = 0; t < nt; ++t) {
        if (near[t]) continue;
        label[t] = componentLabel[std::size_t(findRoot(parent, std::int32_t(t)))];
        if (label[t] == kUnset) continue;
        dist[t] = 0;
        queue.push({0.0, std::int32_t(t)});
    }
    while (!queue.empty()) {
        const auto [d, t] = queue.top();
        queue.pop();
        if (d > dist[std::size_t(t)]) continue;
        const Vec3 c = centroid(m, std::size_t(t));
        for (const std::int32_t u : next[std::size_t(t)]) {
            if (!near[std::size_t(u)] && label[std::size_t(u)] != kUnset) continue;  // labeled by its component
            const double du = d + (centroid(m, std::size_t(u)) - c).norm();
            if (du < dist[std::size_t(u)]) {
                dist[std::size_t(u)] = du;
                label[std::size_t(u)] = label[std::size_t(t)];
                queue.push({du, u});
            }
        }
    }
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        if (adj.groupSize(g) != 2) continue;
        const TetFaceRef& f0 = adj.faces[std::size_t(adj.groupStart[g])];
        const TetFaceRef& f1 = adj.faces[std::size_t(adj.groupStart[g]) + 1];
        const Label l0 = label[std::size_t(f0.tet)], l1 = label[std::size_t(f1.tet)];
        if (l0 == l1 || l0 == kUnset || l1 == kUnset || triangleOf.contains(f0.key) ||
            std::binary_search(facets.begin(), facets.end(), f0.key))
            continue;
        const auto face = outwardFace(m.tets[std::size_t(f0.tet)], f0.local);  // normal out of f0's tet, into f1's
        patch.triangles.push_back({face[0], face[1], face[2]});
        patch.sides.push_back({l1, l0});
    }
    return patch;
}

}  // namespace jawmesh
