// Gmsh MSH 4.1 writer for labeled volume meshes (ASCII or binary): one volume entity per label,
// whose entity tag and physical tag are the label (> 0), physical names from labelName()
// ("bone_mandible", "tooth_24", "pdl_24"). Linear tets are element type 4; quadratic tets type 11.
#pragma once

#include "io/TetMesh.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace jawmesh {

struct GmshWriteOptions {
    bool binary = false;  ///< MSH 4.1 binary (little-endian, size_t = 8 bytes) instead of ASCII
};

/// Node indices of a quadratic tet in Gmsh's order: corners 0..3, then the mid-edge nodes of the
/// edges (0,1), (1,2), (2,0), (3,0), (3,2), (3,1). (VTK swaps the last two; Abaqus/CalculiX C3D10
/// uses (0,1), (1,2), (2,0), (0,3), (1,3), (2,3).)
using Tet10 = std::array<std::int32_t, 10>;

/// Local corner pairs of the mid-edge nodes 4..9 of a Tet10, in Gmsh's order.
constexpr std::array<std::array<int, 2>, 6> kGmshTet10Edges = {{{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}};

/// A mesh that mixes linear and quadratic tets (e.g. Tet10 in the PDL only).
struct MixedTetMesh {
    std::vector<Vec3> nodes;          ///< mm
    std::vector<Tet10> tets;          ///< a linear tet uses the first 4 entries only
    std::vector<Label> labels;        ///< one per tet
    std::vector<std::uint8_t> quadratic;  ///< per tet, 1 = Tet10; empty = every tet quadratic
};

/// Writes `mesh` (Tet4) to `path`, atomically. Element tags are tet index + 1 and node tags node
/// index + 1 (unused nodes are not written), so readGmsh returns the same numbering.
/// Throws Error for tets/labels size mismatch, a label <= 0 or unknown, or I/O failure.
/// Cost: O(nodes + tets); ASCII about 100 bytes per tet.
void writeGmsh(const TetMesh& mesh, const std::string& path, const GmshWriteOptions& options = {});

/// The same for a mixed linear/quadratic mesh (types 4 and 11, one element block per label and type).
void writeGmsh(const MixedTetMesh& mesh, const std::string& path, const GmshWriteOptions& options = {});

}  // namespace jawmesh
