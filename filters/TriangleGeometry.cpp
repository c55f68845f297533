// Implements filters/TriangleGeometry.h; what it computes, its rules and its contract are documented there.
#include "filters/TriangleGeometry.h"

#include "io/Angles.h"

#include <algorithm>
#include <cmath>

namespace jawmesh {

double squaredDistanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).squaredNorm();
}

double squaredDistanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
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

double minAngleDeg(const Vec3& a, const Vec3& b, const Vec3& c) {
    const auto angle = [](const Vec3& o, const Vec3& x, const Vec3& y) {
        const Vec3 u = x - o, v = y - o;
        return std::atan2(u.cross(v).norm(), u.dot(v));
    };
    const double m = std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
    return degrees(m);
}

double smallestAngleCosine(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, bc = c - b, ca = a - c;
    const double lab = ab.norm(), lbc = bc.norm(), lca = ca.norm();
    if (lab == 0 || lbc == 0 || lca == 0) return 1.0;
    return std::max({-ab.dot(ca) / (lab * lca), -ab.dot(bc) / (lab * lbc), -bc.dot(ca) / (lbc * lca)});
}

}  // namespace jawmesh
