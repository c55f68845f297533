// Medit .mesh writer (ASCII, MeshVersionFormatted 2) for labeled tet meshes: the element
// reference is the region label.
#pragma once

#include "io/SurfaceMesh.h"
#include "io/TetMesh.h"

#include <string>
#include <vector>

namespace jawmesh {

/// Optional boundary/interface triangles to write in the Triangles section (indices into the tet
/// mesh's nodes), each with its reference (e.g. tet/Tetrahedralize's interfaceMarker).
struct MeditTriangles {
    std::vector<Tri> triangles;
    std::vector<int> references;  ///< one per triangle
};

/// Writes `mesh` atomically: Vertices (reference 0), Tetrahedra (1-based, reference = label),
/// then Triangles when `triangles` is given and not empty.
/// Throws Error for size mismatches, node indices out of range, or I/O failure. Cost: O(size).
void writeMedit(const TetMesh& mesh, const std::string& path, const MeditTriangles* triangles = nullptr);

}  // namespace jawmesh
