// Sliver improvement of a labeled tet mesh (TetGen's output) by local operations that keep every
// interface: TetGen with a preserved boundary (-Y) cannot split an interface triangle, so it leaves
// slivers wedged between two close interfaces (the 0.2 mm PDL) or at inherited thin triangles.
// The rule and the order of the operations are on improveSlivers below; the driver (passes,
// lookahead) is tet/ImproveSlivers.cpp, the operations are tet/Sliver*.h over tet/TetMeshEditor.h.
#pragma once

#include "io/Progress.h"
#include "io/TetMesh.h"

#include <nlohmann/json.hpp>

#include <cstddef>

namespace jawmesh {

struct SliverOptions {
    double targetMinDihedralDeg = 10.0;  ///< tets below this are worked on
    int maxPasses = 24;                  ///< passes over the remaining bad tets (stops early when none changes anything)
    /// Allow new nodes on interface triangles and edges (the surface keeps its geometry, its
    /// triangles are split); off: interface faces stay exactly as they are.
    bool interfaceInsertions = true;
    /// When the operations above leave bad tets, try each candidate of each operation even when
    /// it does not help at once, improve around it, and keep it when fewer bad tets are left there.
    /// Depth of that lookahead (0: none); each level multiplies its cost by the candidates tried
    /// (docs/BENCHMARKS.md has what each depth leaves on the shared mandible).
    int lookaheadDepth = 1;
    /// A deeper lookahead (when lookaheadDepth > 0), of this depth, after the pushes, when no more
    /// than deepLookaheadTets bad tets are left: its cost grows with the tets it starts from, so it
    /// is kept for the last few. Straight at this depth, not through the ones between: on the
    /// shared mandible depth 2 spent 426 trials on a tet it could not mend, which depth 3 alone
    /// mends in 112 (docs/DESIGN.md).
    int deepLookaheadDepth = 3;
    std::size_t deepLookaheadTets = 8;
    /// Trials the deep lookahead may make in all, nested ones included (a count, not a clock, so
    /// the result does not depend on speed).
    std::size_t deepLookaheadTrials = 500;
    /// Trials the lookahead of depth 1..lookaheadDepth may make in all (a count, so deterministic).
    /// A surface with thousands of tets the hill climbing cannot mend (folds of a damaged input)
    /// would otherwise keep the stage busy for tens of minutes; the clean shared mandible makes
    /// a few hundred (docs/BENCHMARKS.md, session 28).
    std::size_t lookaheadTrials = 5000;
    /// How far the last resort may push an interface node (one inside the mesh, not on its outer
    /// boundary) away from the face opposite it in a tet still under the target, mm (0: never).
    /// The surface moves by at most this much; each node is pushed once at most. For lips a few
    /// thousandths of a millimetre thick that the extraction itself left, which no re-triangulation
    /// fills with good tets.
    double interfacePushMm = 0.005;
    /// The same for a node on the mesh's outer boundary (against the outside: a crown, the bone's
    /// outer surface), mm (0: never), tried only after everything else, and kept only when the
    /// outer surface stays free of self-intersections (tet/SliverPush.h). Issue #27: the slivers
    /// the overlapping-shells surface kept sat on bone and crown lips against the outside, where
    /// the pushes above may not go.
    double outerPushMm = 0.02;
};

struct SliverStats {
    std::size_t badBefore = 0;  ///< tets below the target before / after
    std::size_t badAfter = 0;
    double minDihedralBeforeDeg = 0;
    double minDihedralAfterDeg = 0;
    std::size_t smoothed = 0;   ///< accepted vertex moves
    std::size_t flips23 = 0;
    std::size_t flips32 = 0;
    std::size_t edgeRemovals = 0;  ///< edges with 4..7 tets around them removed
    std::size_t splits = 0;     ///< edges split (one new node each)
    std::size_t faceSplits = 0; ///< faces split (one new node each)
    std::size_t cavityStars = 0; ///< a tet and its same-region neighbours starred from a new node
    std::size_t interfaceInsertions = 0; ///< nodes inserted on an interface triangle or edge (cavities on every side)
    std::size_t lookaheads = 0; ///< operations kept by the lookahead (with what followed them)
    std::size_t lookaheadTrials = 0;   ///< operations the lookahead tried (kept or undone)
    bool lookaheadBudgetSpent = false; ///< the lookahead stopped at SliverOptions::lookaheadTrials
    std::size_t interfacePushes = 0; ///< interface nodes pushed off a thin spot (the last resort), outer ones included
    std::size_t outerPushes = 0;     ///< of those, nodes on the outer boundary
    double largestPushMm = 0;   ///< the longest of those pushes, mm
    int passes = 0;
    double seconds = 0;
};

/// As run.json's tetgen.sliver_improvement records it (counts, angles in degrees, seconds).
nlohmann::json toJson(const SliverStats& stats);

/// Improves `mesh` in place: works on the tets whose smallest dihedral angle is under
/// options.targetMinDihedralDeg (tets positively oriented on input and output; labels kept per
/// region; nodes may be appended, none removed; a node on an interface or the mesh boundary never
/// moves, except interface nodes pushed by at most interfacePushMm; interface triangles may be
/// split by appended nodes on them).
///
/// Rule (tet/SliverScore.h): a tet scores minus the cosine of its smallest dihedral angle. The tets
/// an operation would replace and those it would make are each rated by their worst score and their
/// shortfall (the sum, over tets under the target, of how far under). A candidate is made when it is
/// Pareto-better: neither the worst score nor the shortfall gets worse and one of them improves, so
/// an operation may leave the worst tet as it is and only lift others towards the target.
/// Hill climbing (Klingner & Shewchuk 2007): in passes over the bad tets, worst first, until a pass
/// changes nothing, each tries these in order and makes the first candidate the rule accepts:
///  - smoothing (tet/SliverSmooth.h): a node on no interface moves where its star rates best;
///  - flips inside one region (tet/SliverFlips.h): 2-3, and edge removal of an edge with 3..7 tets
///    around it (the best triangulation of its ring, Shewchuk 2002; 3 tets = the 3-2 flip);
///  - splits inside one region (tet/SliverSplits.h): a new node on an edge or a face, then placed;
///  - cavity star (tet/SliverCavity.h): a new node near the tet starred over a cavity of its region
///    (a flat tet on two boundary faces of a ridge needs a node above it);
///  - interface insertion (tet/SliverInterfaceInsert.h, when options.interfaceInsertions): a new
///    node on an interface triangle or edge of the tet, starred in every region around it.
/// Lookahead (depth 1..lookaheadDepth, deeper only where shallower is stuck): each candidate of each
/// operation but smoothing is made whether it helps or not (none flatter than 1 degree), the bad tets
/// around it are improved as above (with a lookahead one level shallower), and the whole is kept only
/// when, among the tets it changed, fewer are under the target without a lower worst score, or as
/// many with a higher worst score or a Pareto-better rating; otherwise it is undone.
/// Last resort (tet/SliverPush.h): a tet still under the target at an intrinsically thin spot of a
/// region (a lip a few thousandths of a millimetre thick, which no re-triangulation fills with good
/// tets) may have an interface node pushed away from its opposite face, then the hill climbing runs
/// again, then deeper lookaheads when few bad tets are left; what is still left may then have a
/// node of the outer boundary pushed (options.outerPushMm), and the hill climbing runs again.
/// Deterministic: tets are visited by score, ties by index; what runs in parallel (scoring) is
/// compared in a fixed order, so the result does not depend on the thread count.
///
/// `progress` gets the stage "improve slivers" and is polled for cancellation between tets; `stats`,
/// when given, receives what was done.
/// Throws Cancelled when cancelled (the mesh is then partly improved and must not be used), and
/// Error when a region's volume changed beyond what the pushes account for (an internal error).
/// Cost: O(T) to set up plus O(bad tets x star size) per pass; lookahead passes cost far more.
void improveSlivers(TetMesh& mesh, const SliverOptions& options = {}, SliverStats* stats = nullptr,
                    Progress& progress = noProgress());

}  // namespace jawmesh
