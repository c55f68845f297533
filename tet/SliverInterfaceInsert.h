// Interface insertion for the sliver improver (tet/ImproveSlivers.h): a new node on an interface
// triangle or edge of a bad tet, with a cavity starred from it in every region around it. The one
// operation that can mend a sliver wedged between two close interfaces (a PDL one tet thick) or
// with all four nodes on them: TetGen under -Y may not put a node there itself.
#pragma once

#include "tet/ImproveSlivers.h"
#include "tet/SliverScore.h"
#include "tet/TetMeshEditor.h"

#include <cstdint>

namespace jawmesh {

/// Inserts a fixed node on one of t's faces or edges that lie on an interface (or the mesh
/// boundary), so the surface keeps its geometry (the node is on the triangle or segment) and both
/// sides keep sharing their faces. Every region around the node gets a Bowyer-Watson cavity grown
/// from the tets that hold it (tet/SliverCavity.h), starred from it over the cavity's outer faces
/// except those it lies on (their cones are flat; the split interface triangles come out as the
/// new faces through the node).
/// Candidates: the centroid of each interface face of t and the foot of t's opposite node on it
/// (when well inside), the midpoint of each interface edge and its point closest to the opposite
/// edge. Of those the rule accepts, the one with the best objective is made
/// (stats.interfaceInsertions).
bool insertOnInterfaceAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats);

}  // namespace jawmesh
