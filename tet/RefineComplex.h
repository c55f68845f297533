// Local refinement of an interface complex where a tetrahedralization left bad tets: TetGen under
// -Y keeps every interface triangle, so a sliver anchored on the surface comes back on every run
// of the same input. Splitting the surface edges around it at their midpoints changes the local
// point configuration without moving the surface (the midpoints lie on the edges) and the next
// run meshes it differently.
#pragma once

#include "io/InterfaceComplex.h"
#include "io/TetMesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace jawmesh {

/// Splits each listed edge of the complex's surface at its midpoint: every triangle on the edge
/// (one per interface meeting there) becomes two with the same sides and orientation. Edges that
/// are not (or no longer) surface edges are skipped. Returns how many were split.
/// Cost: O(triangles) to index the edges, then O(1) amortised per split.
std::size_t splitComplexEdges(InterfaceComplex& complex, const std::vector<std::array<std::int32_t, 2>>& edges);

/// The surface edges to split around the tets of `mesh` whose smallest dihedral angle is below
/// minDihedralDeg: every edge of such a tet that is an edge of the complex's surface, or, for a
/// tet without one, the longest surface edge at each of its nodes on the surface; each replaced
/// by the end of its longest-edge propagation (the longest edge of both its triangles), and left
/// out where that meets an edge of more than two triangles (a junction of interfaces). Mesh
/// nodes are matched to surface vertices by position (exactly: TetGen keeps the input points).
std::vector<std::array<std::int32_t, 2>> edgesAroundBadTets(const InterfaceComplex& complex, const TetMesh& mesh,
                                                             double minDihedralDeg);

}  // namespace jawmesh
