// Splits inside one region for the sliver improver (tet/ImproveSlivers.h): an edge or a face of a
// bad tet gets a new node, which is then placed by the pattern search of tet/SliverSmooth.h (it
// may leave the edge or face: its star is all the new tets).
#pragma once

#include "tet/ImproveSlivers.h"
#include "tet/SliverScore.h"
#include "tet/TetMeshEditor.h"

#include <cstdint>

namespace jawmesh {

/// Splits an edge of t that lies inside t's region (longest first): the first whose new tets
/// the rule accepts over the edge's ring is made (stats.splits).
bool splitEdgeAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats);

/// Splits a face of t shared with a tet of the same label: the first whose six new tets the rule
/// accepts over the two it replaces is made (stats.faceSplits).
bool splitFaceAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats);

}  // namespace jawmesh
