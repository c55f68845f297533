// Implements filters/SplitCorners.h; what it computes, its rules and its contract are documented there.
#include "filters/SplitCorners.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstdint>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace jawmesh {

namespace {

/// The edges to split this round: per (vertex, region) with exactly three triangles, the longest
/// edge opposite the vertex. Sorted and unique.
std::vector<std::uint64_t> cornerEdges(const InterfaceComplex& c) {
    const auto& V = c.surface.vertices;
    const auto& T = c.surface.triangles;
    std::vector<std::tuple<std::int32_t, Label, std::int32_t>> incidences;  // (vertex, region, triangle)
    incidences.reserve(T.size() * 6);
    for (std::size_t t = 0; t < T.size(); ++t)
        for (Label L : c.sides[t]) {
            if (L == kOutsideLabel) continue;
            for (auto v : T[t]) incidences.emplace_back(v, L, std::int32_t(t));
        }
    tbb::parallel_sort(incidences.begin(), incidences.end());  // distinct tuples: the same order
    std::vector<std::uint64_t> edges;
    for (std::size_t i = 0; i < incidences.size();) {
        std::size_t j = i;
        while (j < incidences.size() && std::get<0>(incidences[j]) == std::get<0>(incidences[i]) &&
               std::get<1>(incidences[j]) == std::get<1>(incidences[i]))
            ++j;
        if (j - i == 3) {
            const std::int32_t v = std::get<0>(incidences[i]);
            double longest = -1;
            std::uint64_t best = 0;
            for (std::size_t k = i; k < j; ++k) {
                const Tri& f = T[std::size_t(std::get<2>(incidences[k]))];
                std::int32_t a = -1, b = -1;
                for (auto x : f)
                    if (x != v) (a < 0 ? a : b) = x;
                const double len = (V[std::size_t(a)] - V[std::size_t(b)]).squaredNorm();
                if (len > longest || (len == longest && edgeKey(a, b) < best)) {
                    longest = len;
                    best = edgeKey(a, b);
                }
            }
            edges.push_back(best);
        }
        i = j;
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

}  // namespace

std::size_t splitThreeTriangleCorners(InterfaceComplex& c) {
    auto& V = c.surface.vertices;
    auto& T = c.surface.triangles;
    std::size_t splits = 0;
    for (;;) {
        const std::vector<std::uint64_t> edges = cornerEdges(c);
        if (edges.empty()) break;
        std::unordered_map<std::uint64_t, std::vector<std::int32_t>> trisOf;
        for (std::size_t t = 0; t < T.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                const std::uint64_t key = edgeKey(T[t][std::size_t(k)], T[t][std::size_t((k + 1) % 3)]);
                if (std::binary_search(edges.begin(), edges.end(), key)) trisOf[key].push_back(std::int32_t(t));
            }
        // One split per triangle per round (a triangle with two edges listed waits a round).
        std::vector<char> touched(T.size(), 0);
        std::size_t round = 0;
        for (std::uint64_t key : edges) {
            const auto& tris = trisOf[key];
            if (std::any_of(tris.begin(), tris.end(), [&](std::int32_t t) { return touched[std::size_t(t)]; })) continue;
            const auto a = std::int32_t(key >> 32), b = std::int32_t(key & 0xffffffffu);
            const auto m = std::int32_t(V.size());
            V.push_back(0.5 * (V[std::size_t(a)] + V[std::size_t(b)]));
            for (std::int32_t t : tris) {
                touched[std::size_t(t)] = 1;
                const Tri f = T[std::size_t(t)];
                int k = 0;  // f[k] -> f[k+1] is the edge (either direction)
                while (edgeKey(f[std::size_t(k)], f[std::size_t((k + 1) % 3)]) != key) ++k;
                const std::int32_t p = f[std::size_t(k)], q = f[std::size_t((k + 1) % 3)], r = f[std::size_t((k + 2) % 3)];
                T[std::size_t(t)] = {p, m, r};
                T.push_back({m, q, r});
                c.sides.push_back(c.sides[std::size_t(t)]);
                touched.push_back(1);
            }
            ++round;
        }
        splits += round;
        if (round == 0) break;  // cannot happen (the first listed edge is always free); no endless loop
    }
    return splits;
}

}  // namespace jawmesh
