// Holes in an interface complex: edges where some region's boundary stops. Every region of a
// complex must be enclosed by its triangles, so around every edge each label lies on the side of
// an even number of triangles (two on a manifold sheet, four or more at junctions). TetGen meshes
// an open complex without complaint, and the tets then flow through the hole from one region into
// the next (tet/Tetrahedralize.h reports that as an open region boundary, after minutes of work).
#pragma once

#include "io/InterfaceComplex.h"

#include <vector>

namespace jawmesh {

struct OpenRegionEdge {
    std::int32_t a, b;  ///< vertex indices, a < b
    Label label;        ///< the region whose boundary is open there
};

/// Every (edge, label) pair where `label` lies on the side of an odd number of the edge's
/// triangles, sorted by (a, b, label). Empty for a closed complex. Cost: O(T log T).
std::vector<OpenRegionEdge> openRegionEdges(const InterfaceComplex& complex);

}  // namespace jawmesh
