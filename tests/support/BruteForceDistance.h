// Point-triangle distance written for the tests, independently of the production code (plane
// projection when it falls inside, else the nearest of the three edges; the production code uses
// Voronoi regions), so tests can check the evaluation's distances against it.
#pragma once

#include "io/SurfaceMesh.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace jawmesh::test {

using Triangle = std::array<Vec3, 3>;

inline double distanceToTriangle(const Vec3& p, const Triangle& t) {
    const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
    const double n2 = n.squaredNorm();
    if (n2 > 0) {
        const Vec3 q = p - n * ((p - t[0]).dot(n) / n2);
        bool inside = true;
        for (int k = 0; k < 3; ++k) inside = inside && (t[(k + 1) % 3] - t[k]).cross(q - t[k]).dot(n) >= 0;
        if (inside) return (p - q).norm();
    }
    double best = INFINITY;
    for (int k = 0; k < 3; ++k) {
        const Vec3 a = t[k], b = t[(k + 1) % 3];
        const double len2 = (b - a).squaredNorm();
        const double s = len2 > 0 ? std::clamp((p - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, (p - (a + s * (b - a))).norm());
    }
    return best;
}

}  // namespace jawmesh::test
