// Implements levelset/CloseHoles.h; what it computes, its rules and its contract are documented there.
#include "levelset/CloseHoles.h"

#include "levelset/LeastAreaLoop.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <tuple>

namespace jawmesh {
namespace {

/// A directed edge of a patch to come: the reverse of an edge that only one triangle uses, so the
/// patch continues that triangle's orientation.
struct PatchEdge {
    std::int32_t from, to;
    std::size_t triangle;  ///< the triangle the hole edge belongs to
};

std::uint64_t edgeKey(std::int32_t a, std::int32_t b) {
    return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
}

/// The edges used by exactly one triangle, as sorted edgeKeys: the edges are bucketed by their
/// lower vertex (a counting sort), so a closed surface, which every run has, costs two linear passes.
std::vector<std::uint64_t> singleUseEdges(const std::vector<Tri>& triangles, std::size_t vertexCount) {
    std::vector<std::uint32_t> start(vertexCount + 1, 0);
    for (const Tri& t : triangles)
        for (int k = 0; k < 3; ++k) ++start[std::size_t(std::min(t[k], t[(k + 1) % 3])) + 1];
    for (std::size_t v = 0; v < vertexCount; ++v) start[v + 1] += start[v];
    std::vector<std::int32_t> upper(3 * triangles.size());
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (const Tri& t : triangles)
        for (int k = 0; k < 3; ++k) {
            const std::int32_t a = t[k], b = t[(k + 1) % 3];
            upper[next[std::size_t(std::min(a, b))]++] = std::max(a, b);
        }
    std::vector<std::uint64_t> single;
    for (std::size_t v = 0; v < vertexCount; ++v) {
        const auto first = upper.begin() + start[v], last = upper.begin() + start[v + 1];
        std::sort(first, last);
        for (auto i = first; i != last;) {
            auto j = i + 1;
            while (j != last && *j == *i) ++j;
            if (j == i + 1) single.push_back(edgeKey(std::int32_t(v), *i));
            i = j;
        }
    }
    return single;
}

/// The patch edges of every edge used by exactly one triangle, sorted by (from, to).
std::vector<PatchEdge> patchEdges(const std::vector<Tri>& triangles, std::size_t vertexCount) {
    const std::vector<std::uint64_t> single = singleUseEdges(triangles, vertexCount);
    std::vector<PatchEdge> edges;
    if (single.empty()) return edges;
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const std::int32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
            if (std::binary_search(single.begin(), single.end(), edgeKey(a, b))) edges.push_back({b, a, t});
        }
    std::sort(edges.begin(), edges.end(), [](const PatchEdge& x, const PatchEdge& y) { return std::tie(x.from, x.to) < std::tie(y.from, y.to); });
    return edges;
}

struct Loop {
    std::vector<std::int32_t> vertices;
    std::size_t triangle = 0;  ///< the triangle along its first edge
};

/// Chains the patch edges into loops; a walk that comes back to a vertex it has passed closes the
/// loop from there (loops touching at a vertex come out separately). Counts the chains that end
/// without closing in `open`.
std::vector<Loop> chainLoops(const std::vector<PatchEdge>& edges, std::size_t& open) {
    std::vector<char> used(edges.size(), 0);
    const auto unusedFrom = [&](std::int32_t v) -> std::ptrdiff_t {
        auto it = std::lower_bound(edges.begin(), edges.end(), v, [](const PatchEdge& e, std::int32_t x) { return e.from < x; });
        for (; it != edges.end() && it->from == v; ++it)
            if (!used[std::size_t(it - edges.begin())]) return it - edges.begin();
        return -1;
    };
    std::vector<Loop> loops;
    for (std::size_t s = 0; s < edges.size(); ++s) {
        if (used[s]) continue;
        used[s] = 1;
        std::vector<std::int32_t> path{edges[s].from};
        std::vector<std::size_t> via{edges[s].triangle};  // via[i]: the triangle of the edge leaving path[i]
        std::map<std::int32_t, std::size_t> at{{edges[s].from, 0}};
        std::size_t cur = s;
        for (;;) {
            const std::int32_t v = edges[cur].to;
            const auto seen = at.find(v);
            if (seen != at.end()) {
                const std::size_t i = seen->second;
                loops.push_back({std::vector<std::int32_t>(path.begin() + std::ptrdiff_t(i), path.end()), via[i]});
                for (std::size_t k = i + 1; k < path.size(); ++k) at.erase(path[k]);
                path.resize(i + 1);
                via.resize(i);
            } else {
                at[v] = path.size();
                path.push_back(v);
            }
            const std::ptrdiff_t next = unusedFrom(v);
            if (next < 0) {
                open += path.size() > 1;
                break;
            }
            used[std::size_t(next)] = 1;
            via.push_back(edges[std::size_t(next)].triangle);
            cur = std::size_t(next);
        }
    }
    return loops;
}

/// The least-area triangulation of the loop over its own vertices (LeastAreaLoop.h), wound as the
/// loop runs, in surface vertex ids; zero-area triangles left out.
std::vector<Tri> leastAreaPatch(const std::vector<Vec3>& vertices, const std::vector<std::int32_t>& loop) {
    std::vector<Vec3> corners;
    for (std::int32_t v : loop) corners.push_back(vertices[std::size_t(v)]);
    std::vector<Tri> patch;
    for (const Tri& t : minimumAreaLoop(corners, [](int, int) { return true; })) {
        const Vec3& a = corners[std::size_t(t[0])];
        if ((corners[std::size_t(t[1])] - a).cross(corners[std::size_t(t[2])] - a).squaredNorm() > 0.0)
            patch.push_back({loop[std::size_t(t[0])], loop[std::size_t(t[1])], loop[std::size_t(t[2])]});
    }
    return patch;
}

}  // namespace

ClosedHoles closeSmallHoles(OrientedSurface& surface, std::size_t maxLoopVertices) {
    ClosedHoles result;
    const std::vector<PatchEdge> edges = patchEdges(surface.triangles, surface.vertices.size());
    if (edges.empty()) return result;
    for (const Loop& loop : chainLoops(edges, result.leftOpen)) {
        if (loop.vertices.size() < 3) continue;
        if (loop.vertices.size() > maxLoopVertices) {
            ++result.leftOpen;
            continue;
        }
        const std::int32_t patchId = surface.patch.empty() ? 0 : surface.patch[loop.triangle];
        for (const Tri& t : leastAreaPatch(surface.vertices, loop.vertices)) {
            surface.triangles.push_back(t);
            if (!surface.patch.empty()) surface.patch.push_back(patchId);
            ++result.triangles;
        }
        ++result.loops;
    }
    return result;
}

}  // namespace jawmesh
