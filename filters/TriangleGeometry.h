// Small exact-enough geometry on single triangles (mm): closest point distance and angles. Shared by
// the simplification (error bound, quality) and by the tests and reports that measure the same things.
#pragma once

#include "io/SurfaceMesh.h"

namespace jawmesh {

/// Squared Euclidean distance from p to the closed triangle a, b, c (degenerate triangles fall back
/// to their longest edge). Ericson, Real-Time Collision Detection, 5.1.5.
double squaredDistanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Squared distance from p to the segment a, b.
double squaredDistanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b);

/// Smallest interior angle of the triangle, degrees (0 for a degenerate triangle).
double minAngleDeg(const Vec3& a, const Vec3& b, const Vec3& c);

/// Cosine of the smallest interior angle (1 for a degenerate triangle): compare angles without atan2.
double smallestAngleCosine(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace jawmesh
