// Which interface vertices lie near a tooth: the simplifier may approximate bone far from the
// teeth more loosely (its shape there matters less to a tooth-load simulation), but keeps the
// alveolar bone around the sockets as tight as the PDL.
#pragma once

#include "io/InterfaceComplex.h"

#include <vector>

namespace jawmesh {

/// Per vertex of `complex`: 1 when it lies within about `distanceMm` of a vertex of a triangle
/// that touches a tooth or a PDL, else 0. "About": distances are measured between cells of a
/// uniform grid of cell distanceMm / 4 along the axes (a cube of half-width distanceMm + one cell
/// around every tooth/PDL cell), so a vertex up to sqrt(3) (distanceMm + 2 cells) away may count
/// as near, and none within distanceMm counts as far. distanceMm <= 0 marks only the vertices of
/// tooth/PDL triangles.
/// Cost: O(vertices + grid cells); the grid covers the complex's bounding box (its cell grows so
/// that it never exceeds ~64 M cells).
std::vector<char> verticesNearTeeth(const InterfaceComplex& complex, double distanceMm);

}  // namespace jawmesh
