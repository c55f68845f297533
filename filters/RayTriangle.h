// Ray-triangle intersection (Möller-Trumbore), for the few places that cast single rays without a
// BVH: region seeds (filters/ShellSeeds) and the labial face of a tooth crown (fe/ToothAxesFromShape).
#pragma once

#include "io/SurfaceMesh.h"

#include <cmath>
#include <limits>

namespace jawmesh {

/// Ray parameter t > 0 of the hit of o + t d with triangle a, b, c, or +inf when the ray misses
/// it (or lies in its plane). d need not be unit; t is in units of |d|. Cost O(1).
inline double rayTriangleHit(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 e1 = b - a, e2 = c - a;
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300) return std::numeric_limits<double>::infinity();
    const double inv = 1.0 / det;
    const Vec3 s = o - a;
    const double u = s.dot(p) * inv;
    if (u < 0 || u > 1) return std::numeric_limits<double>::infinity();
    const Vec3 q = s.cross(e1);
    const double v = d.dot(q) * inv;
    if (v < 0 || u + v > 1) return std::numeric_limits<double>::infinity();
    const double t = e2.dot(q) * inv;
    return t > 0 ? t : std::numeric_limits<double>::infinity();
}

}  // namespace jawmesh
