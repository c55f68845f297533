// Implements filters/HoleFlap.h; what it computes, its rules and its contract are documented there.
#include "filters/HoleFlap.h"

#include <algorithm>

namespace jawmesh {
namespace {

bool inSheet(const InterfaceComplex& c, std::int32_t t, const std::array<Label, 2>& pair) {
    const auto& s = c.sides[std::size_t(t)];
    return std::min(s[0], s[1]) == pair[0] && std::max(s[0], s[1]) == pair[1];
}

}  // namespace

std::vector<std::int32_t> lidInsideLoop(const InterfaceComplex& complex, const VertexTriangles& vt, const HoleLoop& loop,
                                        const std::unordered_set<std::uint64_t>& openEdges, const std::vector<char>& removed) {
    const SurfaceMesh& s = complex.surface;
    BBox box;
    for (const std::int32_t v : loop.vertices) box.extend(s.vertices[std::size_t(v)]);
    const double slack = 0.01 * box.size().norm() + 1e-9;
    box.min.array() -= slack;
    box.max.array() += slack;
    const auto inBox = [&](std::int32_t t) {
        for (const std::int32_t v : s.triangles[std::size_t(t)])
            if (((s.vertices[std::size_t(v)].array() < box.min.array()) || (s.vertices[std::size_t(v)].array() > box.max.array())).any())
                return false;
        return true;
    };
    // Sheet triangles on the far side of edge a-b from t (all of them at a junction).
    const auto across = [&](std::int32_t a, std::int32_t b, std::int32_t t, std::vector<std::int32_t>& out) {
        for (const std::int32_t* u = vt.begin(a); u != vt.end(a); ++u) {
            const Tri& tri = s.triangles[std::size_t(*u)];
            if (*u != t && !removed[std::size_t(*u)] && std::find(tri.begin(), tri.end(), b) != tri.end() && inSheet(complex, *u, loop.pair))
                out.push_back(*u);
        }
    };
    std::vector<std::int32_t> lid, todo;
    std::unordered_set<std::int32_t> seen;
    const std::size_t n = loop.vertices.size();
    for (std::size_t i = 0; i < n; ++i) across(loop.vertices[i], loop.vertices[(i + 1) % n], -1, todo);
    while (!todo.empty()) {
        const std::int32_t t = todo.back();
        todo.pop_back();
        if (!seen.insert(t).second) continue;
        if (!inBox(t)) return {};
        lid.push_back(t);
        const Tri& tri = s.triangles[std::size_t(t)];
        for (int k = 0; k < 3; ++k) {
            const std::int32_t a = tri[std::size_t(k)], b = tri[std::size_t((k + 1) % 3)];
            if (!openEdges.count(edgeKey(a, b))) across(a, b, t, todo);
        }
    }
    std::sort(lid.begin(), lid.end());
    return lid;
}

}  // namespace jawmesh
