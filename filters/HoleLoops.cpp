// Implements filters/HoleLoops.h; what it computes, its rules and its contract are documented there.
#include "filters/HoleLoops.h"

#include "filters/OpenRegionEdges.h"
#include "io/VertexTriangles.h"

#include <algorithm>
#include <map>

namespace jawmesh {
namespace {

/// +1 when triangle t runs a -> b, -1 when b -> a (t contains both).
int direction(const Tri& t, std::int32_t a, std::int32_t b) {
    for (int k = 0; k < 3; ++k)
        if (t[std::size_t(k)] == a) return t[std::size_t((k + 1) % 3)] == b ? 1 : -1;
    return 0;
}

/// Net use of a -> b by the boundary of `region` oriented outward (normals out of the region):
/// zero on a closed boundary, odd where the boundary stops.
int netOutwardUse(const InterfaceComplex& c, const VertexTriangles& vt, std::int32_t a, std::int32_t b, Label region) {
    int net = 0;
    for (const std::int32_t* t = vt.begin(a); t != vt.end(a); ++t) {
        const Tri& tri = c.surface.triangles[std::size_t(*t)];
        if (std::find(tri.begin(), tri.end(), b) == tri.end()) continue;
        const auto& sides = c.sides[std::size_t(*t)];
        if (sides[0] != region && sides[1] != region) continue;
        net += direction(tri, a, b) * (sides[1] == region ? 1 : -1);  // normal points out of sides[1]
    }
    return net;
}

using Outgoing = std::map<std::int32_t, std::vector<std::int32_t>>;  // vertex -> targets

/// Walks the directed edges of one label pair into loops, cutting off a loop whenever the walk
/// comes back to a vertex already on its path. Returns the number of edges left on open chains.
std::size_t chain(Outgoing& out, const std::array<Label, 2>& pair, std::vector<HoleLoop>& loops) {
    std::size_t stray = 0;
    for (auto& [start, targets] : out) {
        while (!targets.empty()) {
            std::vector<std::int32_t> path = {start};
            std::map<std::int32_t, std::size_t> at = {{start, 0}};
            for (;;) {
                auto& next = out[path.back()];
                if (next.empty()) {  // a chain that does not close
                    stray += path.size() - 1;
                    break;
                }
                const std::int32_t v = next.back();
                next.pop_back();
                const auto seen = at.find(v);
                if (seen == at.end()) {
                    at.emplace(v, path.size());
                    path.push_back(v);
                    continue;
                }
                HoleLoop loop{pair, std::vector<std::int32_t>(path.begin() + std::ptrdiff_t(seen->second), path.end())};
                for (std::size_t i = seen->second + 1; i < path.size(); ++i) at.erase(path[i]);
                path.resize(seen->second + 1);
                loops.push_back(std::move(loop));
                if (path.size() == 1 && out[start].empty()) break;
            }
        }
    }
    return stray;
}

}  // namespace

HoleLoops holeLoops(const InterfaceComplex& complex) {
    HoleLoops result;
    const std::vector<OpenRegionEdge> open = openRegionEdges(complex);
    if (open.empty()) return result;
    const VertexTriangles vt = vertexTriangles(complex.surface.triangles, complex.surface.vertices.size());
    std::map<std::array<Label, 2>, Outgoing> byPair;
    for (std::size_t i = 0; i < open.size();) {
        std::size_t j = i;
        while (j < open.size() && open[j].a == open[i].a && open[j].b == open[i].b) ++j;
        if (j - i != 2) {  // sorted by label: a hole in one sheet opens exactly its two labels
            ++result.strayEdges;
            i = j;
            continue;
        }
        const std::array<Label, 2> pair = {open[i].label, open[i + 1].label};
        const std::int32_t a = open[i].a, b = open[i].b;
        // The patch's triangles, normals out of pair[0], cancel the net use of the edge.
        if (netOutwardUse(complex, vt, a, b, pair[0]) > 0) byPair[pair][b].push_back(a);
        else byPair[pair][a].push_back(b);
        i = j;
    }
    for (auto& [pair, out] : byPair) result.strayEdges += chain(out, pair, result.loops);
    return result;
}

}  // namespace jawmesh
