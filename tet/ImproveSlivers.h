// Raises the smallest dihedral angle of a labeled tet mesh by local operations that never touch an
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
//    over their outer faces (a flat tet on two boundary faces of a ridge needs a vertex above it).
// Interface faces, interface vertices and labels never change, so conformity and every region's
// geometry are kept. Serial and deterministic (tets visited by quality, ties by index).
#pragma once

#include "io/TetMesh.h"

#include <cstddef>

namespace jawmesh {

struct SliverOptions {
    double targetMinDihedralDeg = 10.0;  ///< tets below this are worked on
    int maxPasses = 24;                  ///< passes over the remaining bad tets (stops early when none changes anything)
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
    int passes = 0;
    double seconds = 0;
};

/// Improves `mesh` in place (tets positively oriented on input and output; labels kept per region;
/// nodes may be appended, none removed or moved if it lies on an interface or the mesh boundary).
/// Cost: O(T) to set up plus O(bad tets x star size) per pass.
void improveSlivers(TetMesh& mesh, const SliverOptions& options = {}, SliverStats* stats = nullptr);

}  // namespace jawmesh
