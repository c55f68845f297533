// Implements filters/ShellSeeds.h; what it computes, its rules and its contract are documented there.
#include "filters/ShellSeeds.h"

#include "filters/RayTriangle.h"
#include "io/Error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace jawmesh {
namespace {

constexpr int kCandidatesPerShell = 6;

int findRoot(std::vector<int>& parent, int x) {
    while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
    return x;
}

struct RayCandidate {
    Label label;
    std::size_t shell;      // index of the shell in the list of all shells
    std::int32_t triangle;
    Vec3 origin, inward;
    double freeLength = 0;  // distance to the first hit, filled in parallel
};

}  // namespace

std::vector<RegionSeed> seedsInsideShells(const InterfaceComplex& complex) {
    const auto& V = complex.surface.vertices;
    const auto& T = complex.surface.triangles;
    if (complex.sides.size() != T.size()) throw Error("region seeds: one label pair per triangle is required");

    std::map<Label, std::vector<std::int32_t>> byLabel;
    for (std::size_t t = 0; t < T.size(); ++t)
        for (Label L : complex.sides[t])
            if (L != kOutsideLabel) byLabel[L].push_back(std::int32_t(t));

    std::vector<RayCandidate> candidates;
    std::size_t shells = 0;
    for (const auto& [L, tris] : byLabel) {
        // Shells: triangles of L joined across shared edges.
        std::vector<int> parent(tris.size());
        std::iota(parent.begin(), parent.end(), 0);
        std::map<std::pair<std::int32_t, std::int32_t>, int> firstOnEdge;
        for (std::size_t i = 0; i < tris.size(); ++i) {
            const Tri& f = T[std::size_t(tris[i])];
            for (int k = 0; k < 3; ++k) {
                const auto e = std::minmax(f[k], f[(k + 1) % 3]);
                const auto [it, fresh] = firstOnEdge.emplace(std::make_pair(e.first, e.second), int(i));
                if (!fresh) parent[std::size_t(findRoot(parent, int(i)))] = findRoot(parent, it->second);
            }
        }
        std::map<int, std::vector<std::int32_t>> shellTris;
        for (std::size_t i = 0; i < tris.size(); ++i) shellTris[findRoot(parent, int(i))].push_back(tris[i]);
        for (auto& [root, st] : shellTris) {
            const auto area = [&](std::int32_t t) {
                const Tri& f = T[std::size_t(t)];
                return (V[f[1]] - V[f[0]]).cross(V[f[2]] - V[f[0]]).norm();
            };
            std::stable_sort(st.begin(), st.end(), [&](std::int32_t a, std::int32_t b) { return area(a) > area(b); });
            for (std::size_t k = 0; k < st.size() && k < kCandidatesPerShell; ++k) {
                const std::int32_t t = st[k];
                const Tri& f = T[std::size_t(t)];
                const Vec3 n = (V[f[1]] - V[f[0]]).cross(V[f[2]] - V[f[0]]);
                if (n.norm() == 0) continue;
                // the normal points into sides[t][0]: into L when L is sides[t][0]
                const Vec3 inward = (complex.sides[std::size_t(t)][0] == L ? 1.0 : -1.0) * n.normalized();
                candidates.push_back({L, shells, t, (V[f[0]] + V[f[1]] + V[f[2]]) / 3.0, inward, 0});
            }
            ++shells;
        }
    }

    tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t i) {
        RayCandidate& c = candidates[i];
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t t = 0; t < T.size(); ++t) {
            if (std::int32_t(t) == c.triangle) continue;
            const Tri& f = T[t];
            best = std::min(best, rayTriangleHit(c.origin, c.inward, V[f[0]], V[f[1]], V[f[2]]));
        }
        c.freeLength = std::isfinite(best) ? best : 0.0;
    });

    std::vector<const RayCandidate*> bestOfShell(shells, nullptr);
    for (const RayCandidate& c : candidates)
        if (c.freeLength > 0 && (!bestOfShell[c.shell] || c.freeLength > bestOfShell[c.shell]->freeLength))
            bestOfShell[c.shell] = &c;
    std::vector<RegionSeed> seeds;
    for (std::size_t s = 0; s < shells; ++s) {
        const RayCandidate* c = bestOfShell[s];
        if (!c) throw Error("region seeds: a shell of a region has no inward ray (open or degenerate boundary)");
        seeds.push_back({c->origin + 0.5 * c->freeLength * c->inward, c->label});
    }
    std::sort(seeds.begin(), seeds.end(), [](const RegionSeed& a, const RegionSeed& b) {
        if (a.label != b.label) return a.label < b.label;
        return std::lexicographical_compare(a.point.data(), a.point.data() + 3, b.point.data(), b.point.data() + 3);
    });
    return seeds;
}

}  // namespace jawmesh
