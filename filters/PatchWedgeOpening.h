// Opening the sharp wedges of a hole repair. A patch cut from tets (tet/HoleCut.h) follows no
// surface: where one of its triangles meets the sheet around the hole, or another patch triangle, at
// a region wedge of a few degrees, every tet there is a sliver (filters/RegionWedges.h) that no
// improver can mend. Two repair triangles folded onto each other (a fin) have their shared edge
// flipped; a triangle folding against its neighbour is replaced by a fan of three around a point
// lifted off it (a bump). The input's own triangles are never touched.
#pragma once

#include "io/InterfaceComplex.h"

#include <cstddef>
#include <vector>

namespace jawmesh {

struct PatchWedgeStats {
    std::size_t flips = 0;
    std::size_t bumps = 0;
    double smallestWedgeBeforeDeg = 360;  ///< over the repair triangles' edges
    double smallestWedgeAfterDeg = 360;
};

/// Opens the sharp wedges of the triangles with `repair` set (one flag per triangle of `complex`; the
/// repair's). First flips: an edge shared by exactly two repair triangles with the same sides (or the
/// sides the other way round and the opposite winding: the same face) becomes the other diagonal of
/// their quad when the smallest wedge over the five edges that changes is under minWedgeDeg and
/// grows, the new edge is no edge yet, the two new triangles are clean and the tet between the old
/// and the new pair holds no vertex or seed (filters/PatchChecks.h). Then bumps: a repair triangle whose
/// smallest wedge over its edges is under minWedgeDeg becomes the fan (a, b, p), (b, c, p),
/// (c, a, p) around p = its centroid moved along its normal by 1/16 to 1 times its longest edge,
/// either way: the one that opens that wedge most, when the fan is clean and sweeps over no vertex
/// or seed.
/// Either way the complex stays intersection-free and every region keeps its topology (it gains
/// or loses only the swept tets). A bump's triangles are repair triangles in the next pass; passes
/// of each kind repeat while one changes something (at most maxPasses). Triangles in index order:
/// deterministic. `repair` grows with the triangles. Cost: O(T) per change tried (the scan for its
/// neighbours); the repair's triangles are few.
PatchWedgeStats openPatchWedges(InterfaceComplex& complex, std::vector<char>& repair, double minWedgeDeg, int maxPasses = 8);

}  // namespace jawmesh
