// Nodes that no tet uses, dropped: TetGen's hull and the outside's tets leave some when those tets
// are removed, and the sliver improver's edits leave some when they take a node's last tets.
// Every output (run.json, .msh, .vtu, FE decks) then counts and numbers the same nodes.
#pragma once

#include "io/TetMesh.h"

#include <cstddef>

namespace jawmesh {

/// Drops the nodes of `mesh` that no tet uses and renumbers the tets; the other nodes keep their
/// order. Returns the number dropped. O(nodes + tets).
std::size_t dropUnusedNodes(TetMesh& mesh);

}  // namespace jawmesh
