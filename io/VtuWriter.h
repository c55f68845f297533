// VTK XML UnstructuredGrid (.vtu) writer for labeled tet meshes, for ParaView and meshio.
#pragma once

#include "io/TetMesh.h"

#include <string>

namespace jawmesh {

/// Writes `mesh` atomically as a .vtu: Float64 points, Int64 connectivity/offsets, UInt8 cell types
/// (10 = VTK_TETRA), and the Int32 cell data array "label". Data is appended raw binary
/// (little-endian, UInt64 block headers), the compact form ParaView and meshio read.
/// Throws Error for a tets/labels size mismatch, node indices out of range, or I/O failure.
/// Cost: O(nodes + tets), about 70 bytes per tet.
void writeVtu(const TetMesh& mesh, const std::string& path);

}  // namespace jawmesh
