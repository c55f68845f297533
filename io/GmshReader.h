// Gmsh MSH 4.1 reader (ASCII and binary) for labeled tet meshes: lets tests read writers' output
// back and later stages resume from a .msh.
#pragma once

#include "io/TetMesh.h"

#include <string>

namespace jawmesh {

/// Reads the tetrahedra (types 4 and 11; a Tet10 keeps its 4 corners) of a MSH 4.1 file. Each
/// tet's label is the physical tag of its volume entity. Nodes are returned in node-tag order
/// (node i = i-th smallest tag; the writer's tags give back the same indices); tets in element-tag
/// order. Nodes not used by any tet (e.g. mid-edge nodes of Tet10) are kept. Elements of lower
/// dimension are skipped, as are unknown sections.
/// Throws Error(path, reason) for other MSH versions, truncated or malformed data, node tags that
/// are referenced but undefined, a volume entity without exactly one physical tag, or tets of a
/// type other than 4/11. Cost: O(file size), single pass in memory.
TetMesh readGmsh(const std::string& path);

}  // namespace jawmesh
