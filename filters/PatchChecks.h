// The checks a hole patch (filters/FillSurfaceHoles.h) or a change to one (filters/PatchWedgeOpening.h)
// must pass before it is laid into a surface: exactly clean, and no sweep over another piece of the
// surface on its way from the patch it replaces; and the two look-ups patches share.
#pragma once

#include "io/InterfaceComplex.h"
#include "io/SurfaceMesh.h"

#include <cstdint>
#include <vector>

namespace jawmesh {

/// Point v of a patch: a vertex of s, or (v >= s.vertices.size()) one of the patch's new points.
inline const Vec3& patchPoint(const SurfaceMesh& s, const std::vector<Vec3>& added, std::int32_t v) {
    return std::size_t(v) < s.vertices.size() ? s.vertices[std::size_t(v)] : added[std::size_t(v) - s.vertices.size()];
}

/// The triangles of s whose boxes meet `box`, in index order, leaving out those `skip` is true for.
/// Cost: O(T).
template <typename Skip>
std::vector<std::int32_t> trianglesMeeting(const SurfaceMesh& s, const BBox& box, Skip skip) {
    std::vector<std::int32_t> near;
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
        if (!skip(t) && box.overlaps(triangleBox(s, s.triangles[t]))) near.push_back(std::int32_t(t));
    return near;
}

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
