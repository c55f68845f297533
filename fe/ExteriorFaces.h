// The faces of a labeled tet mesh that lie on the outside (no tet on the other side): the exposed
// crowns of teeth and the outer surface of bone. Scenarios pick fixed sets and load patches here.
#pragma once

#include "io/SurfaceMesh.h"
#include "io/TetMesh.h"

#include <vector>

namespace jawmesh {

struct ExteriorFace {
    Tri nodes;      ///< node indices, outward (normal out of the mesh by the right-hand rule)
    Label label;    ///< label of the tet the face belongs to
    std::int32_t tet = -1;    ///< that tet's index
    std::int32_t local = -1;  ///< the face opposite the tet's node `local` (0..3, tet/TetFaceAdjacency.h)
};

/// Every exterior face of `mesh`, in the order of tetFaceAdjacency's groups (sorted by node keys,
/// deterministic). Tets must be positively oriented. Cost: one face adjacency, O(T log T).
std::vector<ExteriorFace> exteriorFaces(const TetMesh& mesh);

/// Area (mm^2) and unit normal of a triangle of `nodes`; the normal is zero for a degenerate face.
double triangleArea(const std::vector<Vec3>& nodes, const Tri& tri);
Vec3 triangleNormal(const std::vector<Vec3>& nodes, const Tri& tri);

}  // namespace jawmesh
