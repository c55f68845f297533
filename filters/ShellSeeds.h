// Region seeds from the surface itself: one point strictly inside every closed shell of every
// region. Needed after simplification, which moves interfaces by up to its error bound, so a seed
// found on the voxel grid can end up outside a thin region (a 1-2 voxel bone sliver) and TetGen
// would then label that region wrongly or not at all.
#pragma once

#include "io/InterfaceComplex.h"

#include <vector>

namespace jawmesh {

/// For every region label L != kOutsideLabel of `complex` and every edge-connected shell of L's
/// boundary: among the shell's largest triangles, casts a ray from the centroid into L and places
/// the seed halfway to the first triangle hit (any interface), choosing the candidate with the
/// longest free segment. The open segment lies inside L by construction, whatever the shell's
/// thickness. A region with a cavity gets one seed per shell, all inside the same component, which
/// TetGen accepts. Sorted by (label, point); deterministic.
/// Throws Error when a shell admits no inward ray (an open or degenerate boundary).
/// Cost: shells x candidates x triangles ray tests (parallel over candidates).
std::vector<RegionSeed> seedsInsideShells(const InterfaceComplex& complex);

}  // namespace jawmesh
