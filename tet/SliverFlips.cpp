// 2-3 flips and edge removal for the sliver improver (tet/SliverFlips.h).
#include "tet/SliverFlips.h"

#include "tet/SliverSmooth.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace jawmesh {
namespace {

/// Replaces `old` by `fresh` (same label, each tet turned positive) when the volume is the same
/// and the rule accepts the new tets' objective over the old ones'.
bool replaceIfAccepted(TetMeshEditor& mesh, const std::vector<std::int32_t>& old, std::vector<Tet> fresh, Acceptance& accept) {
    Objective sNew;
    for (Tet& e : fresh) {
        if (signedVolume6(mesh.node(e[0]), mesh.node(e[1]), mesh.node(e[2]), mesh.node(e[3])) < 0) std::swap(e[2], e[3]);
        sNew.add(sliverScore(mesh.node(e[0]), mesh.node(e[1]), mesh.node(e[2]), mesh.node(e[3])), accept.target());
    }
    if (!mesh.fillsSameVolume(old, fresh)) return false;  // not a re-triangulation of the same volume
    if (!accept(sNew, objectiveOf(mesh, old, accept.target()))) return false;
    mesh.replace(old, fresh, mesh.label(old[0]));
    return true;
}

}  // namespace

bool flip23Around(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats) {
    const Tet e = mesh.tet(t);
    for (int k = 0; k < 4; ++k) {
        const std::int32_t d = e[std::size_t(k)];
        std::int32_t f[3];
        const std::int32_t other = mesh.sameRegionNeighbour(t, k, f);
        if (other < 0) continue;
        std::int32_t apex = -1;
        for (auto v : mesh.tet(other))
            if (v != f[0] && v != f[1] && v != f[2]) apex = v;
        std::vector<Tet> fresh = {{f[0], f[1], d, apex}, {f[1], f[2], d, apex}, {f[2], f[0], d, apex}};
        if (replaceIfAccepted(mesh, {t, other}, fresh, accept)) {
            ++stats.flips23;
            return true;
        }
    }
    return false;
}

bool removeEdgeAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats) {
    const Tet e = mesh.tet(t);
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            std::int32_t a = e[std::size_t(i)], b = e[std::size_t(j)];
            const std::vector<std::int32_t> ring = mesh.interiorRing(a, b, mesh.label(t));
            if (ring.size() < 3 || ring.size() > 7) continue;
            std::vector<std::int32_t> r = ringPolygon(mesh, a, b, ring);
            if (r.size() != ring.size()) continue;
            const std::vector<Tet> fresh = bestRingTriangulation(mesh, a, b, r);
            if (fresh.empty()) continue;
            if (replaceIfAccepted(mesh, ring, fresh, accept)) {
                ++(ring.size() == 3 ? stats.flips32 : stats.edgeRemovals);
                return true;
            }
        }
    return false;
}

std::vector<std::int32_t> ringPolygon(const TetMeshEditor& mesh, std::int32_t a, std::int32_t b, const std::vector<std::int32_t>& ring) {
    std::vector<std::pair<std::int32_t, std::int32_t>> links;
    for (auto s : ring) {
        std::int32_t x[2], n = 0;
        for (auto v : mesh.tet(s))
            if (v != a && v != b) x[n++] = v;
        links.emplace_back(x[0], x[1]);
    }
    std::vector<std::int32_t> r = {links[0].first, links[0].second};
    std::vector<char> used(links.size(), 0);
    used[0] = 1;
    while (r.size() < links.size()) {
        bool found = false;
        for (std::size_t k = 0; k < links.size() && !found; ++k) {
            if (used[k]) continue;
            if (links[k].first == r.back()) r.push_back(links[k].second), found = true;
            else if (links[k].second == r.back()) r.push_back(links[k].first), found = true;
            if (found) used[k] = 1;
        }
        if (!found) return {};
    }
    if (signedVolume6(mesh.node(a), mesh.node(b), mesh.node(r[0]), mesh.node(r[1])) < 0) std::reverse(r.begin(), r.end());
    return r;
}

std::vector<Tet> bestRingTriangulation(const TetMeshEditor& mesh, std::int32_t a, std::int32_t b, const std::vector<std::int32_t>& r) {
    const int n = int(r.size());
    constexpr double kNone = -std::numeric_limits<double>::infinity();
    std::vector<double> q(std::size_t(n * n), kNone);
    std::vector<int> split(std::size_t(n * n), -1);
    const auto at = [n](int i, int j) { return std::size_t(i * n + j); };
    const auto R = [&](int i) -> const Vec3& { return mesh.node(r[std::size_t(i)]); };
    for (int i = 0; i + 1 < n; ++i) q[at(i, i + 1)] = std::numeric_limits<double>::infinity();
    for (int len = 2; len < n; ++len)
        for (int i = 0; i + len < n; ++i) {
            const int j = i + len;
            for (int k = i + 1; k < j; ++k) {
                const double s = std::min({q[at(i, k)], q[at(k, j)], sliverScore(R(i), R(k), R(j), mesh.node(b)),
                                           sliverScore(R(i), R(j), R(k), mesh.node(a))});
                if (s > q[at(i, j)]) {
                    q[at(i, j)] = s;
                    split[at(i, j)] = k;
                }
            }
        }
    if (!(q[at(0, n - 1)] > kInvalidScore)) return {};
    std::vector<Tet> out;
    std::vector<std::pair<int, int>> todo = {{0, n - 1}};
    while (!todo.empty()) {
        const auto [i, j] = todo.back();
        todo.pop_back();
        if (j - i < 2) continue;
        const int k = split[at(i, j)];
        out.push_back({r[std::size_t(i)], r[std::size_t(k)], r[std::size_t(j)], b});
        out.push_back({r[std::size_t(i)], r[std::size_t(j)], r[std::size_t(k)], a});
        todo.push_back({i, k});
        todo.push_back({k, j});
    }
    return out;
}

}  // namespace jawmesh
