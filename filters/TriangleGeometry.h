// Small exact-enough geometry on single triangles (mm): closest point distance and angles. Shared by
// the simplification (error bound, quality) and by the tests and reports that measure the same things.
#pragma once

#include "io/SurfaceMesh.h"

#include <algorithm>

namespace jawmesh {

/// Squared distance from p to the segment a, b.
inline double squaredDistanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).squaredNorm();
}

/// Squared Euclidean distance from p to the closed triangle a, b, c (degenerate triangles fall back
/// to their longest edge). Ericson, Real-Time Collision Detection, 5.1.5. Inline: the evaluation's
/// and the surface stage's closest-triangle loops call it hundreds of millions of times.
inline double squaredDistanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    // Ericson's Voronoi regions. The three vertex regions hold for a degenerate triangle too (the
    // vertex is then the nearest point of its segments); the rest divide, so a degenerate one
    // is measured as its three segments from there on (this test first was a fifth of the cost).
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return ap.squaredNorm();
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return bp.squaredNorm();
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return cp.squaredNorm();
    if (ab.cross(ac).squaredNorm() <= 1e-30 * std::max(ab.squaredNorm(), ac.squaredNorm()) * ac.squaredNorm())
        return std::min({squaredDistanceToSegment(p, a, b), squaredDistanceToSegment(p, b, c),
                         squaredDistanceToSegment(p, c, a)});
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).squaredNorm();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).squaredNorm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).squaredNorm();
    const double denom = 1.0 / (va + vb + vc);
    return (p - (a + ab * (vb * denom) + ac * (vc * denom))).squaredNorm();
}

/// Smallest interior angle of the triangle, degrees (0 for a degenerate triangle).
double minAngleDeg(const Vec3& a, const Vec3& b, const Vec3& c);

/// Cosine of the smallest interior angle (1 for a degenerate triangle): compare angles without atan2.
double smallestAngleCosine(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace jawmesh
