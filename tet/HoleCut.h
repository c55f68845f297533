// The patches for holes no local triangulation could close (filters/FillSurfaceHoles.h), cut from
// a tetrahedralization of the open complex: TetGen meshes through a hole, and its tets there join
// the regions on both sides. Away from the holes (outside a ball around each) the tets are labeled
// by their components, as for the mesh itself; the tets near a hole take the label of the nearest
// labeled tet or input triangle side they reach without crossing the surface (Dijkstra over the
// tets' centroids; a tet on a triangle starts at its centroid's distance from it), so the floods
// from both sides meet midway through the hole, along the sheet's continuation. The tet faces
// where they meet are the patch: faces of a tetrahedralization that conforms to the surface, they
// intersect nothing. (A flood over the whole mesh leaked: the few large tets in the hull's
// concavity carried a label through a hole 20 mm on.)
#pragma once

#include "io/InterfaceComplex.h"
#include "io/TetMesh.h"

#include <array>
#include <vector>

namespace jawmesh {

struct HoleBall {
    Vec3 centre;      ///< mm
    double radiusMm;  ///< covering the hole's loop
};

struct HoleCutPatch {
    /// Tet faces between differently labeled tets that are no input triangle, over mesh.nodes,
    /// wound with their normal into sides[t][0] (the complex's convention).
    std::vector<Tri> triangles;
    std::vector<std::array<Label, 2>> sides;
    /// False when the tets away from the balls already disagree (a hole outside every ball, or
    /// tets reaching across a ball): no patch then.
    bool local = true;
};

/// The patch over the holes of `complex` in `mesh`, a tetrahedralization of it that keeps every
/// input triangle as a tet face (TetGen -Y, the convex hull kept: -c), tets positively oriented;
/// `facets` are sorted node triples of faces that must not be crossed besides the input triangles
/// (TetGen's subfaces); a tet is near a hole when a node or its centroid lies in the hole's ball.
/// With sourcesAtTheirDistance false every tet on a triangle starts at 0 (the floods then meet
/// elsewhere in a hole; a second way when the first leaves a hole of its own).
/// Empty when the complex is closed. Cost: O(T log T) for T tets.
HoleCutPatch holeCutPatch(const InterfaceComplex& complex, const TetMesh& mesh,
                          const std::vector<std::array<std::int32_t, 3>>& facets, const std::vector<HoleBall>& holes,
                          bool sourcesAtTheirDistance = true);

}  // namespace jawmesh
