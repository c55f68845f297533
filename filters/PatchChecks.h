// The checks a hole patch (filters/FillSurfaceHoles.h) or a change to one (filters/PatchWedgeOpening.h)
// must pass before it is laid into a surface: exactly clean, and no sweep over another piece of the
// surface on its way from the patch it replaces.
#pragma once

#include "io/InterfaceComplex.h"
#include "io/SurfaceMesh.h"

#include <cstdint>
#include <vector>

namespace jawmesh {

/// True when a patch is sound: no triangle degenerate, none intersecting (exactly,
/// filters/SelfIntersections.h) another of the patch or a triangle of `near`. The patch's triangles
/// index s.vertices and then `added` (its new points).
bool patchIsClean(const SurfaceMesh& s, const std::vector<Tri>& patch, const std::vector<Vec3>& added,
                  const std::vector<std::int32_t>& near);

/// True when a vertex of the triangles `near` (none of `rim`, the loop both patches span) or a seed
/// lies between two clean patches of one loop, `from` and `to` (each over s.vertices and then its
/// own added points): inside the closed surface that `from` and `to` reversed make (winding
/// number). A patch that passes cannot have swept over any piece of the surface on its way from
/// `from` (a piece between them would have a vertex inside or cross one of the two), nor moved a
/// seed to the other side. Cost: O((vertices of near + seeds) x triangles of both).
bool patchSweepsAVertex(const SurfaceMesh& s, const std::vector<std::int32_t>& near, const std::vector<std::int32_t>& rim,
                        const std::vector<Tri>& from, const std::vector<Vec3>& fromAdded, const std::vector<Tri>& to,
                        const std::vector<Vec3>& toAdded, const std::vector<RegionSeed>& seeds);

}  // namespace jawmesh
