// Triangulations of one closed polygon in space (a hole's boundary loop, filters/HoleLoops.h),
// without any check against other geometry: that is filters/FillSurfaceHoles.h's job.
#pragma once

#include "io/SurfaceMesh.h"
#include "levelset/LeastAreaLoop.h"  // minimumAreaLoop, the third triangulation of a loop

#include <functional>
#include <vector>

namespace jawmesh {

/// Ear clipping of the loop projected onto its Newell plane (the plane its winding defines, so the
/// triangles come out wound as the loop). Each step clips, among the ears whose projected triangle
/// is strictly convex and holds no other loop vertex, the one whose smallest angle (in space) is
/// largest; `diagonalAllowed(i, j)` may veto a diagonal (an edge the surface already has). The
/// triangles index the loop (0..n-1). Empty when it gets stuck (a loop that is far from planar,
/// or folds over itself in projection). Cost: O(n^3) for n loop vertices.
std::vector<Tri> earClipLoop(const std::vector<Vec3>& loop, const std::function<bool(int, int)>& diagonalAllowed);

/// The fan from an added vertex (index n, the loop's centroid) to every loop edge, wound as the loop.
std::vector<Tri> centroidFan(std::size_t n);

/// Newell's normal: the area vector of the closed polygon (twice its area in the Newell plane), its
/// direction given by the winding.
Vec3 newellNormal(const std::vector<Vec3>& loop);

/// The loop's centroid (mean of its vertices), where centroidFan puts its apex.
Vec3 loopCentroid(const std::vector<Vec3>& loop);

/// The largest distance between two loop vertices, mm: the size of a hole.
double loopDiameterMm(const std::vector<Vec3>& loop);

}  // namespace jawmesh
