// Self-intersection check of a triangle surface: every pair of triangles that meet anywhere other
// than at the vertices / edges they share (by index). Broad phase: Embree's rtcCollide on a user
// geometry (one box per triangle). Narrow phase: exact predicates (orient3d / orient2d with a
// floating-point filter and an exact expansion-arithmetic fallback), so touching, coplanar and
// folded configurations are decided exactly, not by a tolerance.
#pragma once

#include "io/SurfaceMesh.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace jawmesh {

struct SelfIntersectionReport {
    /// Intersecting triangle pairs (i < j), sorted. Two triangles that share an edge intersect only
    /// when they fold onto each other (coplanar, same side); sharing a vertex, only when they meet
    /// elsewhere too. Triangles with the same three vertices count as intersecting.
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
    /// Triangles with a repeated vertex index or zero area (exactly collinear corners), sorted.
    std::vector<std::int32_t> degenerate;
    bool clean() const { return pairs.empty() && degenerate.empty(); }
};

/// Finds all intersecting triangle pairs and all degenerate triangles of mesh; with `only` (one
/// flag per triangle), only the pairs with a flagged triangle and the flagged degenerate ones (a
/// surface changed in a few places since a clean check).
/// Result does not depend on the thread count. Throws Error if an index is out of range.
/// Cost: O(n log n) broad phase plus exact tests on the pairs whose boxes overlap; about a second
/// per million triangles on a typical desktop (2 threads).
SelfIntersectionReport findSelfIntersections(const SurfaceMesh& mesh, const std::vector<char>* only = nullptr);

/// Exact test for two triangles given by corner positions and vertex indices (indices decide what
/// is shared: equal indices are the same point). True when they intersect other than at shared
/// vertices / along a shared edge, as for findSelfIntersections; false when either triangle repeats
/// an index (degenerate: findSelfIntersections reports those apart). Cost: a few dozen predicates.
bool trianglesIntersect(const Vec3 a[3], const Tri& ia, const Vec3 b[3], const Tri& ib);

/// Exact sign of det[a - d; b - d; c - d] (Shewchuk's orient3d): +1 when d lies below the plane
/// through a, b, c (a, b, c counter-clockwise seen from above), -1 above, 0 when coplanar.
int orient3dExact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// True when the triangle a, b, c has exactly collinear corners.
bool triangleDegenerate(const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace jawmesh
