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

/// Tets around a node that moves, with what does not move precomputed: per tet the other three
/// corners (in the order that puts the node first), the normal of the face opposite it, and the
/// sign the tet's orientation takes in that order. Scoring a position then costs three cross
/// products a tet instead of five (the pattern search scores hundreds of positions per star).
struct MovingStar {
    struct Corners {
        Vec3 a = Vec3::Zero(), b = Vec3::Zero(), c = Vec3::Zero();  ///< the fixed corners
        Vec3 opposite = Vec3::Zero();  ///< (b - a) x (c - a)
        double oppositeLength = 0;     ///< its norm
        double sign = 1;               ///< +1 or -1: valid when sign * (a - p) . opposite > 0
        bool moves = true;             ///< false: the tet does not hold the node (its score is `fixedScore`)
        double fixedScore = kInvalidScore;
    };
    std::vector<Corners> tets;
    /// Indices into `tets`, the worst-scoring at the search's current position first (bestPosition
    /// ranks them): a trial that cannot win is found out after a tet or two (empty: no screening).
    std::vector<std::uint32_t> worstFirst;
};

/// The star of node v over `tets` (by nodes of `nodes`).
MovingStar movingStar(const std::vector<Vec3>& nodes, const std::vector<Tet>& tets, std::int32_t v);

/// The objective of `star` with its node placed at p (scores as tet/SliverScore.h's, up to
/// rounding), summed in the order of `star.tets`; stops at the first invalid tet in that order.
/// Returns Objective::hopeless() when the tets are worse than `cannotBeat` in either part (a
/// trial with an invalid tet is, when cannotBeat's worst score is valid): found by scoring in
/// star.worstFirst order, stopping as soon as the tets so far are (the worst score only falls and
/// the shortfall only grows), so a trial that can no longer win costs a tet or two; one that
/// survives is scored again in `tets` order, so its objective has the same bits whatever the
/// ranking.
Objective objectiveWith(const MovingStar& star, const Vec3& p, double target, const Objective& cannotBeat = Objective::hopeless());

/// The same for the tets `tets` (by nodes of `nodes`) with node v placed at p.
Objective objectiveWith(const std::vector<Vec3>& nodes, const std::vector<Tet>& tets, std::int32_t v, const Vec3& p, double target,
                        const Objective& cannotBeat = Objective::hopeless());

/// The objective of the editor's tets `tets` where they are.
Objective objectiveOf(const TetMeshEditor& mesh, const std::vector<std::int32_t>& tets, double target);

/// Pattern search (14 directions, step halved when none helps) for the position of node v with
/// the best objective over `tets`, from `start`; returns that position and objective (the
/// start's if nothing is betterThan it). The 14 trials of a step are scored in order, each only
/// as far as it can still beat the best so far (a star takes microseconds: scoring them in
/// parallel only kept TBB's workers spinning, 3.8 of the mandible's 17 CPU seconds of the tet stage).
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
