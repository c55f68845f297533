// The plane quadric of Garland and Heckbert: the weighted sum of squared distances to a set of
// planes, as one symmetric 4x4 matrix. The simplification ranks its collapses by it.
#pragma once

#include "io/SurfaceMesh.h"

namespace jawmesh {

/// Symmetric 4x4 plane quadric (Garland-Heckbert): sum of w * (n.p + d)^2.
struct Quadric {
    double q[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    /// Adds the plane n.p + d = 0 (n of unit length) with weight w (an area, mm^2).
    void addPlane(const Vec3& n, double d, double w) {
        const double a = n.x(), b = n.y(), c = n.z();
        const double v[10] = {a * a, a * b, a * c, a * d, b * b, b * c, b * d, c * c, c * d, d * d};
        for (int i = 0; i < 10; ++i) q[i] += w * v[i];
    }
    void add(const Quadric& o) {
        for (int i = 0; i < 10; ++i) q[i] += o.q[i];
    }
    /// The weighted sum of squared distances from p to the planes (mm^4 with area weights).
    double eval(const Vec3& p) const {
        const double x = p.x(), y = p.y(), z = p.z();
        return q[0] * x * x + 2 * q[1] * x * y + 2 * q[2] * x * z + 2 * q[3] * x + q[4] * y * y + 2 * q[5] * y * z +
               2 * q[6] * y + q[7] * z * z + 2 * q[8] * z + q[9];
    }
};

}  // namespace jawmesh
