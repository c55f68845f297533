// Implements filters/TriangleGeometry.h; what it computes, its rules and its contract are documented there.
#include "filters/TriangleGeometry.h"

#include "io/Angles.h"

#include <algorithm>
#include <cmath>

namespace jawmesh {

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
