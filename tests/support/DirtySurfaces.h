// Corruptions of a closed surface as segmentation exports make them (issues #9 and #27), shared by
// the tests and bench/bench_soak: flipped faces, holes, duplicated faces, triangle soups,
// overlapping shells. Deterministic for a given seed.
#pragma once

#include "io/SurfaceMesh.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

namespace jawmesh::test {

inline SurfaceMesh flipped(SurfaceMesh m) {
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    return m;
}

/// Reverses a random half of the triangles (fixed seed).
inline SurfaceMesh flipHalf(SurfaceMesh m, unsigned seed = 7) {
    std::mt19937 rng(seed);
    for (auto& t : m.triangles)
        if (rng() & 1u) std::swap(t[1], t[2]);
    return m;
}

/// Removes every triangle whose centroid lies within a random radius in [rMin, rMax] (mm) of
/// `count` random surface points (triangle centroids, fixed seed); `holes`, when given, receives
/// each hole's centre and radius.
inline SurfaceMesh punchHoles(const SurfaceMesh& m, int count, double rMin, double rMax, unsigned seed = 11,
                              std::vector<std::pair<Vec3, double>>* holesOut = nullptr) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::size_t> pick(0, m.triangles.size() - 1);
    std::uniform_real_distribution<double> radius(rMin, rMax);
    auto centroid = [&](const Tri& t) {
        return (m.vertices[static_cast<std::size_t>(t[0])] + m.vertices[static_cast<std::size_t>(t[1])] +
                m.vertices[static_cast<std::size_t>(t[2])]) / 3.0;
    };
    std::vector<std::pair<Vec3, double>> holes;
    for (int i = 0; i < count; ++i) {
        const Vec3 c = centroid(m.triangles[pick(rng)]);
        holes.emplace_back(c, radius(rng));
    }
    SurfaceMesh out;
    out.vertices = m.vertices;
    for (const Tri& t : m.triangles) {
        const Vec3 c = centroid(t);
        const bool inHole = std::any_of(holes.begin(), holes.end(), [&](const auto& h) { return (c - h.first).norm() < h.second; });
        if (!inHole) out.triangles.push_back(t);
    }
    if (holesOut) *holesOut = holes;
    return out;
}

/// Appends copies of a random `fraction` of the triangles: half reuse the vertex indices, half
/// get their own copies of the vertices (so only welding finds them), some reversed.
inline SurfaceMesh duplicateFaces(SurfaceMesh m, double fraction, unsigned seed = 13) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const std::size_t n = m.triangles.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (u(rng) >= fraction) continue;
        Tri t = m.triangles[i];
        if (rng() & 1u) {
            for (auto& v : t) {
                m.vertices.push_back(m.vertices[static_cast<std::size_t>(v)]);
                v = static_cast<std::int32_t>(m.vertices.size() - 1);
            }
        }
        m.triangles.push_back(t);
    }
    return m;
}

/// Every triangle with its own three vertices, in shuffled order: a soup with no shared vertex.
inline SurfaceMesh unwelded(const SurfaceMesh& m, unsigned seed = 17) {
    std::vector<Tri> order = m.triangles;
    std::shuffle(order.begin(), order.end(), std::mt19937(seed));
    SurfaceMesh out;
    for (const Tri& t : order) {
        Tri u;
        for (int k = 0; k < 3; ++k) {
            out.vertices.push_back(m.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])]);
            u[static_cast<std::size_t>(k)] = static_cast<std::int32_t>(out.vertices.size() - 1);
        }
        out.triangles.push_back(u);
    }
    return out;
}

/// `a` followed by `b`, on their own vertices (not welded): two shells as one file holds them.
inline SurfaceMesh concatenated(SurfaceMesh a, const SurfaceMesh& b) {
    const auto offset = static_cast<std::int32_t>(a.vertices.size());
    a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
    for (Tri t : b.triangles) {
        for (auto& v : t) v += offset;
        a.triangles.push_back(t);
    }
    return a;
}

/// The surface plus a copy of it scaled by `scale` about its vertex centroid (an inner shell, as
/// a pulp or dentin shell in a micro-CT export), concatenated: overlapping closed shells.
inline SurfaceMesh withInnerShell(const SurfaceMesh& m, double scale) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : m.vertices) c += v / static_cast<double>(m.vertices.size());
    SurfaceMesh inner = m;
    for (Vec3& v : inner.vertices) v = c + scale * (v - c);
    return concatenated(m, inner);
}

}  // namespace jawmesh::test
