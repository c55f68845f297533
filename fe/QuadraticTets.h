// Linear tets -> quadratic tets (Tet10) with mid-edge nodes shared between every tet of an edge, so
// the quadratic mesh stays conformal. Writers reorder the mid-edge nodes into their format's order.
#pragma once

#include "io/GmshWriter.h"
#include "io/SurfaceMesh.h"
#include "io/TetMesh.h"

#include <cstdint>
#include <unordered_map>

namespace jawmesh {

/// Mid-edge node of each edge, keyed by edgeKey(a, b) (io/SurfaceMesh.h).
using EdgeMidNodes = std::unordered_map<std::uint64_t, std::int32_t>;

/// Every tet of `mesh` as a Tet10 in Gmsh's node order (kGmshTet10Edges): the corner nodes keep
/// their indices, one node per distinct edge is appended at the edge midpoint (straight edges), in
/// order of first appearance (tets in order, edges in Gmsh order), so the numbering is
/// deterministic. `mids` (optional) receives the mid-edge node of every edge.
/// Cost: O(T) with a hash map of about 1.2 T edges.
MixedTetMesh quadraticTetMesh(const TetMesh& mesh, EdgeMidNodes* mids = nullptr);

/// Abaqus / CalculiX C3D10 (and FEBio tet10) order of a Gmsh-ordered Tet10: corners, then the
/// mid-edge nodes of (0,1), (1,2), (2,0), (0,3), (1,3), (2,3).
inline Tet10 abaqusOrderFromGmsh(const Tet10& g) { return {g[0], g[1], g[2], g[3], g[4], g[5], g[6], g[7], g[9], g[8]}; }

}  // namespace jawmesh
