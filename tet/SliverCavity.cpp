// Circumsphere cavities, their stars and the cavity star operation (tet/SliverCavity.h).
#include "tet/SliverCavity.h"

#include "tet/SliverSmooth.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace jawmesh {

bool insideCircumsphere(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& q) {
    const Vec3 u = b - a, v = c - a, w = d - a;
    const double det = 2 * u.dot(v.cross(w));
    if (det == 0) return false;
    const Vec3 centre = (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / det;
    return (q - a - centre).squaredNorm() < centre.squaredNorm();
}

void growCircumsphereCavity(const TetMeshEditor& mesh, std::vector<std::int32_t>& cavity, const Vec3& q) {
    for (std::size_t i = 0; i < cavity.size() && cavity.size() < 64; ++i)
        for (int k = 0; k < 4; ++k) {
            std::int32_t f[3];
            const std::int32_t s = mesh.sameRegionNeighbour(cavity[i], k, f);
            if (s < 0 || std::find(cavity.begin(), cavity.end(), s) != cavity.end()) continue;
            const Tet& g = mesh.tet(s);
            if (insideCircumsphere(mesh.node(g[0]), mesh.node(g[1]), mesh.node(g[2]), mesh.node(g[3]), q)) cavity.push_back(s);
        }
}

namespace {

/// The tet of the region behind the outer face f of `cavity` (-1: the region's boundary).
std::int32_t tetBehind(const TetMeshEditor& mesh, const std::vector<std::int32_t>& cavity, const std::int32_t f[3]) {
    for (auto c : cavity) {
        const Tet& g = mesh.tet(c);
        int opposite = -1, shared = 0;
        for (int k = 0; k < 4; ++k) {
            if (std::find(f, f + 3, g[std::size_t(k)]) != f + 3) ++shared;
            else opposite = k;
        }
        if (shared != 3) continue;
        std::int32_t face[3];
        return mesh.sameRegionNeighbour(c, opposite, face);
    }
    return -1;
}

}  // namespace

bool growUntilStarShaped(const TetMeshEditor& mesh, std::vector<std::int32_t>& cavity, const Vec3& q, const FaceFilter& skip) {
    while (cavity.size() <= 64) {
        bool grown = false;
        const std::vector<Tet> star = starOfCavity(mesh, cavity, skip);
        for (const Tet& x : star) {
            const Vec3* p[4];
            int hole = 0;
            for (int k = 0; k < 4; ++k) {
                if (x[std::size_t(k)] < 0) hole = k;
                p[k] = x[std::size_t(k)] < 0 ? &q : &mesh.node(x[std::size_t(k)]);
            }
            if (signedVolume6(*p[0], *p[1], *p[2], *p[3]) > 0) continue;
            std::int32_t f[3];
            int n = 0;
            for (int k = 0; k < 4; ++k)
                if (k != hole) f[n++] = x[std::size_t(k)];
            const std::int32_t behind = tetBehind(mesh, cavity, f);
            if (behind < 0) return false;
            if (std::find(cavity.begin(), cavity.end(), behind) == cavity.end()) {
                cavity.push_back(behind);
                grown = true;
                break;
            }
        }
        if (!grown) return true;
    }
    return false;
}

std::vector<Tet> starOfCavity(const TetMeshEditor& mesh, const std::vector<std::int32_t>& cavity, const FaceFilter& skip) {
    std::vector<std::array<std::int32_t, 3>> keys;
    for (auto c : cavity)
        for (int i = 0; i < 4; ++i) {
            std::array<std::int32_t, 3> key{};
            int n = 0;
            for (int j = 0; j < 4; ++j)
                if (j != i) key[std::size_t(n++)] = mesh.tet(c)[std::size_t(j)];
            std::sort(key.begin(), key.end());
            keys.push_back(key);
        }
    // A face two cavity tets share is inside the cavity. Counted in a sorted copy: the scan of
    // every key for every face was quadratic in the cavity, a tenth of a small run's CPU.
    std::vector<std::array<std::int32_t, 3>> sorted = keys;
    std::sort(sorted.begin(), sorted.end());
    const auto shared = [&](const std::array<std::int32_t, 3>& key) {
        const auto range = std::equal_range(sorted.begin(), sorted.end(), key);
        return range.second - range.first > 1;
    };
    std::vector<Tet> star;
    for (std::size_t ci = 0; ci < cavity.size(); ++ci)
        for (int i = 0; i < 4; ++i) {
            if (shared(keys[4 * ci + std::size_t(i)])) continue;
            if (skip && skip(keys[4 * ci + std::size_t(i)])) continue;
            Tet x = mesh.tet(cavity[ci]);
            x[std::size_t(i)] = -1;
            star.push_back(x);
        }
    return star;
}

namespace {

/// Where cavity star tries a new node for t: its centroid, then, on each face of t on the
/// region's boundary, where the apex of a regular tet on that face would be and lower (a tet with
/// one boundary face is best mended by a node above that face), then points above each edge of t
/// shared by two boundary faces.
std::vector<Vec3> cavityStarts(const TetMeshEditor& mesh, std::int32_t t) {
    const Tet e = mesh.tet(t);
    const auto P = [&](std::int32_t v) -> const Vec3& { return mesh.node(v); };
    std::vector<Vec3> starts;
    starts.push_back(0.25 * (P(e[0]) + P(e[1]) + P(e[2]) + P(e[3])));
    // Faces of t on the region's boundary, with their normals pointing out of t.
    std::vector<std::pair<int, Vec3>> boundary;
    for (int k = 0; k < 4; ++k) {
        std::int32_t f[3];
        if (mesh.sameRegionNeighbour(t, k, f) >= 0) continue;
        const Vec3 n = (P(f[1]) - P(f[0])).cross(P(f[2]) - P(f[0]));
        const Vec3 out = (P(f[0]) - P(e[std::size_t(k)])).dot(n) > 0 ? n : Vec3(-n);
        boundary.emplace_back(k, out.normalized());
    }
    for (const auto& [k, out] : boundary) {
        const Vec3& a = P(e[std::size_t((k + 1) % 4)]);
        const Vec3& b = P(e[std::size_t((k + 2) % 4)]);
        const Vec3& c = P(e[std::size_t((k + 3) % 4)]);
        const double meanEdge = ((a - b).norm() + (b - c).norm() + (c - a).norm()) / 3.0;
        const double regularHeight = std::sqrt(2.0 / 3.0) * meanEdge;
        for (double h : {1.0, 0.7, 0.45}) starts.push_back((a + b + c) / 3.0 - h * regularHeight * out);
    }
    for (std::size_t i = 0; i < boundary.size(); ++i)
        for (std::size_t j = i + 1; j < boundary.size(); ++j) {
            // the edge shared by the faces opposite nodes k1 and k2: the other two nodes
            const int k1 = boundary[i].first, k2 = boundary[j].first;
            Vec3 a = Vec3::Zero();
            for (int v = 0; v < 4; ++v)
                if (v != k1 && v != k2) a += 0.5 * P(e[std::size_t(v)]);
            const Vec3 in = -(boundary[i].second + boundary[j].second).normalized();
            const double len = (P(e[std::size_t(k1)]) - P(e[std::size_t(k2)])).norm();
            for (double h : {0.15, 0.3, 0.45, 0.6, 0.9}) starts.push_back(a + h * len * in);
        }
    return starts;
}

}  // namespace

bool starCavityAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats) {
    for (const Vec3& q : cavityStarts(mesh, t)) {
        std::vector<std::int32_t> cavity{t};
        growCircumsphereCavity(mesh, cavity, q);
        if (!growUntilStarShaped(mesh, cavity, q)) continue;
        std::vector<Tet> tets = starOfCavity(mesh, cavity);
        const std::int32_t m = mesh.addNode(q, false);
        for (Tet& x : tets)
            for (auto& v : x)
                if (v < 0) v = m;
        const auto [p, after] = bestPosition(mesh, tets, m, q, accept.target());
        mesh.placeNewNode(p);
        if (!accept(after, objectiveOf(mesh, cavity, accept.target())) || !mesh.fillsSameVolume(cavity, tets)) {
            mesh.dropNewNode();
            continue;
        }
        mesh.replace(cavity, tets, mesh.label(t));
        ++stats.cavityStars;
        return true;
    }
    return false;
}

}  // namespace jawmesh
