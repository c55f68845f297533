// Flips inside one region for the sliver improver (tet/ImproveSlivers.h): the 2-3 flip of a face
// and edge removal (Shewchuk 2002), whose 3-tet case is the 3-2 flip. Each re-triangulates a
// cavity of one label, checked by positive orientation and volume conservation.
#pragma once

#include "tet/ImproveSlivers.h"
#include "tet/SliverScore.h"
#include "tet/TetMeshEditor.h"

#include <cstdint>
#include <vector>

namespace jawmesh {

/// 2-3 flip of a face of t whose other tet has t's label: the first (faces in t's node order)
/// the rule accepts is made (stats.flips23).
bool flip23Around(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats);

/// Edge removal: an edge of t inside t's region with 3..7 tets around it is replaced by the best
/// triangulation of its ring polygon joined to the edge's two ends; the first the rule accepts is
/// made (stats.flips32 for 3 tets, stats.edgeRemovals otherwise).
bool removeEdgeAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats);

/// The ring nodes of edge (a, b) around its tets `ring`, in cyclic order, oriented so that
/// (a, b, r[k], r[k+1]) is positive; empty when the ring is not one closed cycle.
std::vector<std::int32_t> ringPolygon(const TetMeshEditor& mesh, std::int32_t a, std::int32_t b, const std::vector<std::int32_t>& ring);

/// Triangulation of the ring polygon r maximising the smallest score of the tets it makes with a
/// (below) and b (above), by dynamic programming; empty when every one gives an invalid tet.
std::vector<Tet> bestRingTriangulation(const TetMeshEditor& mesh, std::int32_t a, std::int32_t b, const std::vector<std::int32_t>& r);

}  // namespace jawmesh
