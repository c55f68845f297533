// A cheap floating-point filter in front of the exact triangle-pair test (SelfIntersections.h):
// most pairs near an edge collapse are clearly apart, and this says so without predicates.
#pragma once

#include "io/SurfaceMesh.h"

namespace jawmesh {

/// True when every corner of triangle b not shared with triangle a (shared = same index in ia,
/// ib) lies clearly on one side of a's plane (margin far above rounding), so they cannot intersect
/// other than at what they share; for two triangles on one edge, when their apexes lie clearly on
/// opposite sides of the edge. False means "test exactly", not "they intersect".
bool separatedByPlane(const Vec3 a[3], const Tri& ia, const Vec3 b[3], const Tri& ib);

}  // namespace jawmesh
