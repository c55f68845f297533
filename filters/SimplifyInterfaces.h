// Interface complex -> far fewer triangles, same regions: feature- and topology-preserving edge
// collapses with a guaranteed error bound and no self-intersections.
//
// Operation: half-edge collapses u -> v (u disappears, v keeps its position, so every output vertex
// is an input vertex lying on the fine interface), cheapest first by the quadric error of u's planes
// at v (Garland-Heckbert). A collapse is made only when all of these hold:
//  - features: a vertex inside one interface moves anywhere in it; a vertex on a junction curve
//    (where three or more regions meet, or two interfaces of different label pairs) moves only
//    along that curve; corners of the curve network never move. So every triangle keeps its label
//    pair and every junction curve stays a polyline through its input vertices.
//  - topology: the link condition on the whole complex (Dey et al. 1999), so no region vanishes,
//    splits or changes genus, and no two triangles come to share their three vertices.
//  - error: every input vertex removed so far stays within the bound of its interface (label
//    pair; on bone / outside looser far from the teeth; on a thin plate, PlateThickness.h, a
//    quarter of the plate's thickness at most) of the output triangles of that
//    interface, and every removed curve vertex within the bound of its curve (tracked exactly;
//    the reported maximum is this one-sided Hausdorff distance from the input vertices to the
//    output); the other way, the centroid, edge midpoints and the centroids of the halves an edge
//    split makes (SplitCorners.h) of every new triangle stay within
//    the bound of the input surface (distance to the input triangles around the nearest input
//    vertex of the collapse, an upper bound of the true distance).
//  - quality: no new triangle has an angle below minAngleDeg unless it replaces a triangle that
//    was already worse, no normal turns by more than maxNormalTurnDeg, no new edge is longer than
//    the interface's maximum edge (on a thin plate, 4 times its thickness), and no region comes to
//    span less than minWedgeDeg around an edge (RegionWedges.h: such a wedge caps the dihedral
//    angles of every tet in it).
//  - intersections: each new triangle is tested exactly (filters/SelfIntersections.h predicates)
//    against the triangles around the collapse; the whole output is then checked (Embree broad
//    phase, exact predicates) and, if two sheets met elsewhere, everything is redone testing each
//    new triangle against every triangle its box meets (a uniform grid), which cannot miss.
// Parallel by blocks (SimplifyOptions::blockMm); deterministic whatever the thread count (blocks
// are independent and merged in a fixed order; ties broken by vertex ids).
// Implementation: SimplifyPasses.h (blocks and passes), BlockSimplifier.h (the collapse queue of
// a block), CollapseCheck.h (the conditions above, in order), BlockMesh.h (a block's mesh).
#pragma once

#include "filters/AdaptiveCells.h"
#include "filters/InterfaceBounds.h"
#include "io/InterfaceComplex.h"
#include "io/Progress.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <map>
#include <string>

namespace jawmesh {

struct SimplifyOptions {
    double toothErrorMm = 0.02;   ///< bound on tooth / outside and the crest cap (PDL / outside), mm
    double pdlErrorMm = 0.02;     ///< bound on tooth / PDL and PDL / bone (well under a 0.05 mm voxel)
    double boneErrorMm = 0.08;    ///< bound on bone / outside within boneNearTeethMm of a tooth or PDL
    double boneFarErrorMm = 0.15; ///< bound on bone / outside farther away (max with boneErrorMm)
    double boneNearTeethMm = 2.0; ///< "near a tooth" (filters/NearTeeth.h)
    double pdlMaxEdgeMm = 0.4;    ///< longest new edge on tooth/PDL and PDL/bone (TetGen -Y keeps them)
    double capMaxEdgeMm = 0.065;  ///< on PDL / outside (the crest cap): >= 3 triangles across 0.2 mm
    double toothMaxEdgeMm = 1.0;  ///< on tooth / outside (crowns)
    double boneMaxEdgeMm = 2.5;   ///< on bone / outside
    /// Smallest angle a collapse may create (see file comment). 20 degrees kept 4-7x more triangles
    /// (measured on the phantom: 178 k vs 42 k at 15) for no gain in tet quality after
    /// tet/ImproveSlivers.h; below ~15 the tets on thin triangles stay slivers.
    double minAngleDeg = 15.0;
    double maxNormalTurnDeg = 60.0;
    /// Smallest angle a region (not the outside) may come to span around an edge (RegionWedges.h):
    /// the tets there can be no better. Collapses may not create a smaller one, nor shrink one
    /// that was already smaller. 0 = off.
    double minWedgeDeg = 20.0;
    /// Thin plates (PlateThickness.h: a region between two nearly parallel sheets, measured near
    /// the teeth up to this thickness, mm; 0 = off): a collapse may move a plate's sheet by at
    /// most plateErrorFraction of its thickness and give it no new edge longer than
    /// plateEdgeFactor times it, so the tets across it can keep their angles (about atan(T / L)).
    double plateMaxMm = 0.1;
    double plateErrorFraction = 0.25;
    double plateEdgeFactor = 4.0;
    /// Parallel passes over cubic blocks of this edge (border vertices frozen, then blocks shifted
    /// by half, then by a quarter), then one serial pass over what can still collapse; 0 = a
    /// serial pass over everything only. The result does not depend on the thread count.
    double blockMm = 6.0;
    /// Test every new triangle against all triangles its box meets. Off: only against the
    /// triangles around the collapse (folds, junctions), and if the output check then finds an
    /// intersection the whole simplification is redone with this on.
    bool exhaustiveIntersectionChecks = false;
};

struct SimplifyStats {
    std::size_t inputTriangles = 0;
    std::size_t outputTriangles = 0;
    std::size_t outputVertices = 0;
    std::size_t collapses = 0;
    /// Output triangles per interface kind ("tooth/pdl", "pdl/bone", "tooth/outside", "pdl/outside",
    /// "bone/outside", "other").
    std::map<std::string, std::size_t> trianglesPerKind;
    double maxErrorMm = 0;         ///< largest tracked distance of an input vertex to its output interface
    double maxErrorNearTeethMm = 0;  ///< the same over input vertices near a tooth (NearTeeth.h)
    double minAngleDeg = 0;        ///< smallest angle over the output triangles
    /// Output triangles by smallest angle: [0,5) [5,10) [10,15) [15,20) [20,30) [30,40) [40,60] degrees.
    std::array<std::size_t, 7> minAngleHistogram{};
    double seconds = 0;
    bool exhaustiveRerun = false;  ///< the local intersection test missed one: redone exhaustively
    std::size_t cornerSplits = 0;     ///< edges split so no region has a 3-triangle corner (SplitCorners.h)
    std::size_t plateVertices = 0;    ///< input vertices on a thin plate (SimplifyOptions::plateMaxMm)
    double minWedgeDeg = 360;         ///< smallest region wedge of the output (RegionWedges.h)
    std::size_t edgesBelowMinWedge = 0; ///< output edges with a wedge under SimplifyOptions::minWedgeDeg
};

/// The stats as recorded in run.json and `jawmesh surface --json`.
nlohmann::json toJson(const SimplifyStats& stats);

/// The options as recorded in `jawmesh surface`'s summary.
nlohmann::json toJson(const SimplifyOptions& options);

/// The error bounds of `options`, per interface (shared with the adaptive extraction).
InterfaceBounds boundsOf(const SimplifyOptions& options);

/// `adaptive` with what the adaptive extraction must share with the simplification set from
/// `options`: the bounds, the near-teeth distance and the smallest region wedge.
AdaptiveOptions matchedTo(const SimplifyOptions& options, AdaptiveOptions adaptive = {});

/// Interface kind of a label pair, as used in SimplifyStats and reports.
std::string interfaceKind(Label a, Label b);

/// Simplifies `input` (an extracted interface complex: closed regions, consistent label pairs, no
/// self-intersections). Seeds are placed anew inside every shell of every region of the output
/// (filters/ShellSeeds.h). The output, its three-triangle corners split (filters/SplitCorners.h),
/// is checked exactly for intersecting and degenerate triangles as handed on: Throws Error when
/// that check finds one (which means the input had one) or the options are invalid; Cancelled
/// when progress is cancelled.
/// Cost: O(n log n) in the input triangles; memory about 215 bytes per input triangle.
InterfaceComplex simplifyInterfaces(const InterfaceComplex& input, const SimplifyOptions& options = {},
                                    Progress& progress = noProgress(), SimplifyStats* stats = nullptr);

}  // namespace jawmesh
