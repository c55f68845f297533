// An icosphere made in code, the round test shape of every stage's tests.
#pragma once

#include "io/SurfaceMesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace jawmesh::test {

/// Outward icosphere of radius r (mm) around c; subdivisions >= 0 (20 * 4^s triangles).
inline SurfaceMesh icosphere(double r, int subdivisions, const Vec3& c = Vec3::Zero()) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    SurfaceMesh m;
    m.vertices = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                  {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    m.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                   {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                   {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (auto& v : m.vertices) v.normalize();
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            m.vertices.push_back((m.vertices[static_cast<std::size_t>(a)] + m.vertices[static_cast<std::size_t>(b)]).normalized());
            const int id = static_cast<int>(m.vertices.size() - 1);
            mid.emplace(key, id);
            return id;
        };
        std::vector<Tri> next;
        for (const Tri& f : m.triangles) {
            const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), d = midpoint(f[2], f[0]);
            next.push_back({f[0], a, d});
            next.push_back({f[1], b, a});
            next.push_back({f[2], d, b});
            next.push_back({a, b, d});
        }
        m.triangles = std::move(next);
    }
    for (auto& v : m.vertices) v = c + r * v;
    return m;
}

}  // namespace jawmesh::test
