// Raises the smallest dihedral angle of a labeled tet mesh by local operations that never move an
// interface: TetGen with a preserved boundary (-Y) cannot split an interface triangle, so it leaves
// slivers wedged between two close interfaces (the 0.2 mm PDL) or at inherited thin triangles.
//
// Operations, tried in this order on every tet below the target, each made only when it raises
// the smallest dihedral angle among the tets it changes (hill climbing, Klingner & Shewchuk 2007):
//  - smoothing: a vertex inside one region (on no interface) moves to where its star's smallest
//    dihedral angle is largest (pattern search; no star tet may invert);
//  - flips inside one region: 2-3 (a face whose two tets have the same label) and edge removal
//    (an edge whose 3..7 tets have the same label and whose ring is closed: the best triangulation
//    of the ring, Shewchuk 2002; 3 tets = the 3-2 flip), checked by positive orientation and
//    volume conservation;
//  - splits: an edge or a face inside one region gets a new vertex, which is then smoothed;
//  - cavity star: a tet and its same-region neighbours are replaced by the star of a new vertex
//    over their outer faces (a flat tet on two boundary faces of a ridge needs a vertex above it);
//  - interface insertion, last: a new vertex on an interface triangle or edge of the tet, with a
//    cavity starred from it in every region around it (a sliver wedged between two interfaces a
//    PDL apart, or with all four nodes on interfaces, cannot be mended from inside one region).
// Where none of these raises a bad tet's neighbourhood any more (a local optimum of the hill
// climbing), a lookahead makes each candidate of each operation anyway, improves around it as
// above and keeps the whole only when fewer bad tets are left there; otherwise it is undone.
// Last, a tet still under the target at an intrinsically thin spot of a region (a lip a few
// thousandths of a millimetre thick, which no re-triangulation fills with good tets) may have its
// interface node that lies lowest over its opposite face pushed away from that face, by at most
// SliverOptions::interfacePushMm: the only operation that moves the surface, within that bound.
// Otherwise interface vertices never move and labels never change; interface triangles are only
// split by a vertex on them, so conformity and every region's geometry are kept. Serial and
// deterministic (tets visited by quality, ties by index).
#pragma once

#include "io/TetMesh.h"

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
    /// Depth of that lookahead (0: none). On the shared mandible 41 tets under 10 degrees are left
    /// without it, 12 with depth 1 (+7 s), 6 with depth 2 (+270 s).
    int lookaheadDepth = 1;
    /// Deeper lookaheads (when lookaheadDepth > 0), up to this depth, after the pushes, when no
    /// more than deepLookaheadTets bad tets are left: their cost grows with the tets they start
    /// from, so they are kept for the last few (the adaptive mandible surface: 3 left, 0 at depth 2).
    int deepLookaheadDepth = 2;
    std::size_t deepLookaheadTets = 8;
    /// Trials each deeper level may make in all, nested ones included (a count, not a clock, so the
    /// result does not depend on speed; 200: 2.5 s on the thin-lip test, enough for the mandible).
    std::size_t deepLookaheadTrials = 200;
    /// How far the last resort may push an interface node (one inside the mesh, not on its outer
    /// boundary) away from the face opposite it in a tet still under the target, mm (0: never).
    /// The surface moves by at most this much; each node is pushed once at most. On the shared
    /// mandible the two tets left under 10 degrees sat on lips 0.002-0.009 mm thick in the fine
    /// extraction itself.
    double interfacePushMm = 0.005;
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
    std::size_t interfacePushes = 0; ///< interface nodes pushed off a thin spot (the last resort)
    double largestPushMm = 0;   ///< the longest of those pushes, mm
    int passes = 0;
    double seconds = 0;
};

/// Improves `mesh` in place (tets positively oriented on input and output; labels kept per region;
/// nodes may be appended, none removed or moved if it lies on an interface or the mesh boundary,
/// except interface nodes pushed by at most interfacePushMm; interface triangles may be split by
/// appended nodes on them).
/// Cost: O(T) to set up plus O(bad tets x star size) per pass.
void improveSlivers(TetMesh& mesh, const SliverOptions& options = {}, SliverStats* stats = nullptr);

}  // namespace jawmesh
