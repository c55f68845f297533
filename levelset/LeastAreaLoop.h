// The least-area triangulation of a closed loop in space, shared by the level sets' hole patches
// (levelset/CloseHoles.h) and the surface's hole filling (filters/FillSurfaceHoles.h through
// filters/TriangulateLoop.h). In levelset/ because the level sets, the lower layer, use it.
#pragma once

#include "io/SurfaceMesh.h"

#include <functional>
#include <vector>

namespace jawmesh {

/// The triangulation of the loop (no added vertex) of least total area, by dynamic programming
/// over its sub-polygons (Barequet & Sharir; Liepa's hole filling): for loops that are not flat,
/// such as a staircase of missing tile faces, where a projection folds. Diagonals that
/// `diagonalAllowed` vetoes are never used. Empty when every triangulation uses a vetoed diagonal.
/// Cost: O(n^3) time, O(n^2) memory.
std::vector<Tri> minimumAreaLoop(const std::vector<Vec3>& loop, const std::function<bool(int, int)>& diagonalAllowed);

}  // namespace jawmesh
