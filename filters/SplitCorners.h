// Splits the surface where a region's boundary has only three triangles around a vertex. TetGen,
// told to keep the surface (-Y), must then make the tet of that vertex and its three neighbours,
// and when the three triangles are nearly coplanar (a junction vertex on a smooth surface, common
// after simplification) that tet is a sliver no interior operation can repair: all of its
// vertices and three of its faces are fixed. Splitting the edge opposite the vertex at its
// midpoint gives the region four triangles there without moving the surface at all.
#pragma once

#include "io/InterfaceComplex.h"

#include <cstddef>

namespace jawmesh {

/// Until every vertex has at least four triangles of every region it bounds (outside excluded):
/// splits, for each vertex with three, the longest edge opposite it at its midpoint, in every
/// triangle that has that edge (label pairs and orientation kept). Geometry is unchanged (new
/// vertices lie on existing edges), so regions stay closed and intersection-free. Seeds are kept.
/// Returns the number of edges split. Deterministic. Cost: O(T) per round, a few rounds.
std::size_t splitThreeTriangleCorners(InterfaceComplex& complex);

}  // namespace jawmesh
