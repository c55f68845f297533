// Implements tet/RefineComplex.h; what it computes, its rules and its contract are documented there.
#include "tet/RefineComplex.h"

#include "io/SurfaceMesh.h"
#include "tet/ElementQuality.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>
#include <unordered_set>

namespace jawmesh {

namespace {

/// Triangles on each surface edge.
std::unordered_map<std::uint64_t, std::vector<std::size_t>> trianglesByEdge(const SurfaceMesh& s) {
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> byEdge;
    byEdge.reserve(s.triangles.size() * 2);
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
        for (int i = 0; i < 3; ++i) byEdge[edgeKey(s.triangles[t][std::size_t(i)], s.triangles[t][std::size_t((i + 1) % 3)])].push_back(t);
    return byEdge;
}

struct PositionHash {
    std::size_t operator()(const Vec3& p) const {
        std::uint64_t h = 1469598103934665603ull;
        for (int i = 0; i < 3; ++i) {
            std::uint64_t bits;
            const double x = p[i] == 0.0 ? 0.0 : p[i];  // -0 and +0 alike
            std::memcpy(&bits, &x, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
        return std::size_t(h);
    }
};

}  // namespace

std::size_t splitComplexEdges(InterfaceComplex& c, const std::vector<std::array<std::int32_t, 2>>& edges) {
    auto& s = c.surface;
    auto byEdge = trianglesByEdge(s);
    std::size_t split = 0;
    const auto replace = [&](std::uint64_t key, std::size_t from, std::size_t to) {
        for (auto& t : byEdge[key])
            if (t == from) t = to;
    };
    for (const auto& e : edges) {
        const auto it = byEdge.find(edgeKey(e[0], e[1]));
        if (it == byEdge.end() || it->second.empty()) continue;
        const std::vector<std::size_t> on = it->second;
        byEdge.erase(it);
        const auto m = std::int32_t(s.vertices.size());
        s.vertices.push_back(0.5 * (s.vertices[std::size_t(e[0])] + s.vertices[std::size_t(e[1])]));
        for (std::size_t t : on) {
            const Tri tri = s.triangles[t];
            int i = 0;
            while (!((tri[std::size_t(i)] == e[0] && tri[std::size_t((i + 1) % 3)] == e[1]) ||
                     (tri[std::size_t(i)] == e[1] && tri[std::size_t((i + 1) % 3)] == e[0])))
                ++i;
            const std::int32_t a = tri[std::size_t(i)], b = tri[std::size_t((i + 1) % 3)], o = tri[std::size_t((i + 2) % 3)];
            const std::size_t u = s.triangles.size();
            s.triangles[t] = Tri{a, m, o};
            s.triangles.push_back(Tri{m, b, o});
            c.sides.push_back(c.sides[t]);
            byEdge[edgeKey(a, m)].push_back(t);
            byEdge[edgeKey(m, b)].push_back(u);
            byEdge[edgeKey(m, o)].push_back(t);
            byEdge[edgeKey(m, o)].push_back(u);
            replace(edgeKey(b, o), t, u);
        }
        ++split;
    }
    return split;
}

std::vector<std::array<std::int32_t, 2>> edgesAroundBadTets(const InterfaceComplex& c, const TetMesh& mesh, double minDihedralDeg) {
    const auto& s = c.surface;
    std::unordered_map<Vec3, std::int32_t, PositionHash> vertexAt;
    vertexAt.reserve(s.vertices.size());
    for (std::size_t v = 0; v < s.vertices.size(); ++v) vertexAt.emplace(s.vertices[v], std::int32_t(v));
    const auto byEdge = trianglesByEdge(s);
    // Longest surface edge at each vertex (for tets without a surface edge).
    std::vector<std::int32_t> longest(s.vertices.size(), -1);
    std::vector<double> longestLen(s.vertices.size(), -1.0);
    for (const Tri& t : s.triangles)
        for (int i = 0; i < 3; ++i) {
            const std::int32_t a = t[std::size_t(i)], b = t[std::size_t((i + 1) % 3)];
            const double len = (s.vertices[std::size_t(a)] - s.vertices[std::size_t(b)]).norm();
            for (auto [x, y] : {std::pair{a, b}, std::pair{b, a}})
                if (len > longestLen[std::size_t(x)] || (len == longestLen[std::size_t(x)] && y < longest[std::size_t(x)]))
                    longestLen[std::size_t(x)] = len, longest[std::size_t(x)] = y;
        }
    const auto length = [&](std::int32_t a, std::int32_t b) { return (s.vertices[std::size_t(a)] - s.vertices[std::size_t(b)]).norm(); };
    // Longest-edge propagation (Rivara's LEPP): the edge actually split is the longest edge of both
    // its triangles, so no triangle is cut across a short side (children keep at least half the
    // parent's smallest angle). Edges where more than two triangles meet (junctions of several
    // interfaces) are left alone: TetGen 1.5.0 was seen to abort on such splits.
    const auto lepp = [&](std::int32_t a, std::int32_t b, std::array<std::int32_t, 2>& out) {
        for (int step = 0; step < 16; ++step) {
            const auto it = byEdge.find(edgeKey(a, b));
            if (it == byEdge.end() || it->second.size() != 2) return false;
            bool longest = true;
            for (std::size_t t : it->second) {
                const Tri& tri = s.triangles[t];
                for (int i = 0; i < 3 && longest; ++i) {
                    const std::int32_t x = tri[std::size_t(i)], y = tri[std::size_t((i + 1) % 3)];
                    if (edgeKey(x, y) != edgeKey(a, b) && length(x, y) > length(a, b)) a = x, b = y, longest = false;
                }
                if (!longest) break;
            }
            if (longest) {
                out = {std::min(a, b), std::max(a, b)};
                return true;
            }
        }
        return false;
    };
    std::vector<std::array<std::int32_t, 2>> out;
    std::unordered_set<std::uint64_t> seen;
    const auto add = [&](std::int32_t a, std::int32_t b) {
        std::array<std::int32_t, 2> e;
        if (lepp(a, b, e) && seen.insert(edgeKey(e[0], e[1])).second) out.push_back(e);
    };
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const auto& e = mesh.tets[t];
        const auto& n = mesh.nodes;
        if (tetShape(n[std::size_t(e[0])], n[std::size_t(e[1])], n[std::size_t(e[2])], n[std::size_t(e[3])]).minDihedralDeg >= minDihedralDeg)
            continue;
        std::int32_t sv[4];
        for (int k = 0; k < 4; ++k) {
            const auto it = vertexAt.find(n[std::size_t(e[std::size_t(k)])]);
            sv[k] = it == vertexAt.end() ? -1 : it->second;
        }
        bool any = false;
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j)
                if (sv[i] >= 0 && sv[j] >= 0 && byEdge.count(edgeKey(sv[i], sv[j]))) add(sv[i], sv[j]), any = true;
        if (!any)
            for (int k = 0; k < 4; ++k)
                if (sv[k] >= 0 && longest[std::size_t(sv[k])] >= 0) add(sv[k], longest[std::size_t(sv[k])]);
    }
    return out;
}

}  // namespace jawmesh
