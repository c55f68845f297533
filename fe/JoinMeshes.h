// Two labeled tet meshes as one, sharing no node: the two jaws of a biting scenario are meshed
// apart (one `jawmesh run` folder each) and touch only through the solver's contact.
#pragma once

#include "io/TetMesh.h"

namespace jawmesh {

/// The union of `first` and `second`: nodes of `first`, then those of `second` (its tets
/// renumbered), labels kept. Throws Error when a label occurs in both (the same jaw given twice).
/// Cost: O(nodes + tets).
TetMesh joinMeshes(const TetMesh& first, const TetMesh& second);

}  // namespace jawmesh
