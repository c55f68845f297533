// Smoothing for the sliver improver (tet/ImproveSlivers.h): a node inside one region moves to where
// the worst tet of its star is best (a pattern search on the objective of tet/SliverScore.h). The
// same search places the node a split or a cavity star inserts (tet/SliverSplits.h, SliverCavity.h).
#pragma once

#include "tet/ImproveSlivers.h"
#include "tet/SliverScore.h"
#include "tet/TetMeshEditor.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace jawmesh {

/// The objective of the tets `tets` (by nodes of `nodes`) with node v placed at p; stops at the
/// first invalid tet, and returns Objective::hopeless() as soon as the tets so far are worse than
/// `cannotBeat` in either part (a trial that can no longer win is not scored to the end).
Objective objectiveWith(const std::vector<Vec3>& nodes, const std::vector<Tet>& tets, std::int32_t v, const Vec3& p, double target,
                        const Objective& cannotBeat = Objective::hopeless());

/// The objective of the editor's tets `tets` where they are.
Objective objectiveOf(const TetMeshEditor& mesh, const std::vector<std::int32_t>& tets, double target);

/// Pattern search (14 directions, step halved when none helps) for the position of node v with
/// the best objective over `tets`, from `start`; returns that position and objective (the
/// start's if nothing is betterThan it). Deterministic: the 14 trials of a step are scored in
/// parallel and compared in order.
std::pair<Vec3, Objective> bestPosition(const TetMeshEditor& mesh, const std::vector<Tet>& tets, std::int32_t v, Vec3 start,
                                        double target);

/// bestPosition for a new node m from two starts: where it was put (on the split edge or face,
/// where a flat sliver keeps its new tets flat) and the centroid of the replaced tets `old` (off
/// that plane).
std::pair<Vec3, Objective> bestOfStarts(const TetMeshEditor& mesh, const std::vector<Tet>& fresh, std::int32_t m,
                                        const std::vector<std::int32_t>& old, double target);

/// Moves the first node of tet t that is not fixed and whose best position the rule accepts over
/// where it is (the star of the node is what changes). True when a node moved (stats.smoothed).
bool smoothAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats);

}  // namespace jawmesh
