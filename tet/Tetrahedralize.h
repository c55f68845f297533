// Labeled, quality tetrahedral mesh of a multi-material interface complex, with TetGen 1.5: holes
// repaired first (tet/RepairHoles.h), TetGen run through tet/TetgenAdapter.h on a ladder of
// settings (tet/Tetrahedralize.cpp), tets labeled from the interface sides (tet/LabelFromSides.h),
// slivers improved (tet/ImproveSlivers.h), optional refinement rounds (tet/RefineComplex.h).
#pragma once

#include "filters/FillSurfaceHoles.h"
#include "io/InterfaceComplex.h"
#include "io/Progress.h"
#include "io/TetMesh.h"
#include "tet/ImproveSlivers.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace jawmesh {

/// Quality and sizing targets. Edge lengths are in mm and become TetGen volume bounds through the
/// volume of a regular tet of that edge (L^3 / (6 sqrt 2)); 0 leaves that region unbounded.
struct TetOptions {
    double radiusEdgeRatio = 1.5;   ///< TetGen -q bound on circumradius / shortest edge (> 1.0)
    /// Dihedral bound given to TetGen's refinement (-q/<deg>) when >= 0; below 0 it is the target,
    /// slivers.targetMinDihedralDeg. TetGen refines with Steiner points towards it; the sliver
    /// improvement after TetGen always aims at the target.
    double tetgenMinDihedralDeg = -1.0;
    double boneEdgeMm = 0.0;        ///< target edge length in bone (coarse)
    double toothEdgeMm = 0.0;       ///< target edge length in teeth (medium)
    double pdlEdgeMm = 0.0;         ///< target edge length in PDL (fine)
    double maxEdgeMm = 0.0;         ///< bound everywhere (TetGen -a<volume>), 0 = none
    bool preserveBoundary = true;   ///< -Y: no Steiner points on the interface triangles
    /// TetGen merges adjacent coplanar facets and re-triangulates them unless told not to (-M);
    /// kept off so the output surface is exactly the input triangles.
    bool mergeCoplanarFacets = false;
    int optimizationLevel = 3;      ///< TetGen -O level (0..9), all local operations (scheme 7)
    /// Check the surface for intersecting and degenerate triangles first (exactly): TetGen 1.5.0
    /// crashes instead of throwing on intersecting facets, so turning this off is only safe for
    /// input known to be clean (simplifyInterfaces' output). A surface the stage repaired
    /// (tet/RepairHoles.h) is checked either way.
    bool checkIntersections = true;
    /// Extra TetGen runs (the rungs of tet/Tetrahedralize.cpp's ladder, at most 2) while tets under
    /// the target are left.
    int repairAttempts = 2;
    /// After TetGen, raise tets below the target by smoothing, flips and splits inside the
    /// regions (tet/ImproveSlivers.h); interfaces are untouched but for its last resort's pushes.
    bool improveSlivers = true;
    /// That improvement's options. Its targetMinDihedralDeg is the stage's target minimum dihedral
    /// angle of every tet, degrees, in [0, 70): TetGen's -q/<deg> unless tetgenMinDihedralDeg is
    /// set, the improver's target, and what the repair runs and refinement rounds count tets under.
    SliverOptions slivers;
    /// Rounds of local refinement when tets under the target are left: the surface edges
    /// around them are split at their midpoints (the surface does not move) and the kept run is
    /// repeated on the refined complex, while that leaves fewer (tet/RefineComplex.h). 0 here
    /// (the surface's own points only); `run` allows 3 (cli/RunOptions.cpp, docs/DESIGN.md: the
    /// surface does not move, and the simplifier checks the centroids of a split's halves, but
    /// not those of a second split's quarters).
    int refineRounds = 0;
    /// When tets under the target are left after every rung and round, the improver runs once more
    /// on the kept mesh with its interface pushes reaching this far, mm (0, or no interface pushes
    /// at all in `slivers`: never; config key tet_final_push_mm), and that mesh is kept when it
    /// leaves fewer such tets, or as many with a larger smallest angle. Only then:
    /// a mesh that meets the target never sees it (session 42: the same push everywhere moved the
    /// shared maxilla to another rung, 861 k tets against 565 k). A node already pushed may move
    /// by this much again. For the bent lips of a voxel staircase's faces (docs/BENCHMARKS.md).
    double finalInterfacePushMm = 0.01;
};

/// What a run did, for run.json and the report.
struct TetStats {
    std::string switches;               ///< TetGen switches of the run that was kept
    int attempts = 0;                   ///< TetGen runs made (1 + repair runs)
    double seconds = 0;                 ///< wall time of all TetGen runs
    std::size_t inputVertices = 0;
    std::size_t inputTriangles = 0;
    std::size_t nodes = 0;
    std::size_t tets = 0;
    std::size_t outsideTetsRemoved = 0; ///< tets in enclosed cavities without a seed (attribute 0)
    double minDihedralDeg = 0;
    double maxRadiusEdge = 0;
    std::size_t belowMinDihedral = 0;   ///< tets still below options.slivers.targetMinDihedralDeg (0 when met)
    SliverStats slivers;                ///< what the sliver improvement did on the kept run
    std::vector<std::string> failedAttempts; ///< repair runs that failed (switches: reason); the kept run stands
    int refineRounds = 0;               ///< refinement rounds kept (TetOptions::refineRounds)
    std::size_t refinedEdges = 0;       ///< surface edges split by them
    /// What the last improvement with the longer pushes did (TetOptions::finalInterfacePushMm),
    /// when it ran; finalPushKept tells whether its mesh was kept.
    std::optional<SliverStats> finalPush;
    bool finalPushKept = false;
    /// Peak resident memory of the child processes TetGen ran in (one group of regions,
    /// tet/TetgenGroups.h; the refinement rounds), bytes: not part of this process's peak, but
    /// alongside it while they run.
    std::uint64_t childPeakMemoryBytes = 0;
    /// Holes the input complex had and the patches that closed them before TetGen ran
    /// (filters/FillSurfaceHoles.h); inputVertices / inputTriangles count the complex as given.
    HoleFillStats holeRepair;
};

/// As run.json's "tetgen" records it: switches, attempts, failed_attempts, refine_rounds,
/// refined_edges, child_peak_memory_bytes, seconds, hole_repair, sliver_improvement and final_push
/// (null when it did not run, else kept and its improvement).
nlohmann::json toJson(const TetStats& stats);

/// TetGen volume bound (mm^3) for a target edge length (mm): the volume of a regular tet.
double tetVolumeForEdge(double edgeMm);

/// Per seed of `plc`, the TetGen volume bound of its region's kind from the options' edge
/// lengths, mm^3 (-1: unbounded): TetgenRun::seedVolumeBoundsMm3 as the stage sets it.
std::vector<double> seedVolumeBounds(const InterfaceComplex& plc, const TetOptions& options);

/// TetGen's switches for the first run of tetrahedralize's ladder with these options.
std::string firstTetgenSwitches(const TetOptions& options);


/// Note on -Y: TetGen cannot refine a region that is one tet thick between preserved facets (a
/// thin PDL), so there the interface triangle size sets the element size; with
/// preserveBoundary = false TetGen may split interface triangles (still conformal, same geometry).
/// Tetrahedralizes the region interiors of `plc` with TetGen (switches p, q, A, a, Y, M, O, z, Q):
/// every interface triangle becomes a facet (marker = interfaceMarker of its sides), each seed a
/// region whose volume bound follows its kind. With preserveBoundary, tet labels are read from the
/// sides of the interface triangles around each group of tets, so a missing or misplaced seed
/// cannot mislabel a region (without it, from the seeds' TetGen attributes). Tets on the outside
/// side of an interface (enclosed cavities) are dropped; unused nodes are removed; tets are oriented
/// positively; slivers are then improved (tet/ImproveSlivers.h). When the minimum dihedral is
/// still below the target (options.slivers.targetMinDihedralDeg), TetGen is re-run with stronger optimisation up to
/// options.repairAttempts times and the best mesh is kept (stats->belowMinDihedral says whether
/// the bound was met); the refinement rounds (options.refineRounds) come before the last of those
/// runs, which makes far more tets.
/// Throws Error when the complex is malformed (sizes, indices, no seeds, seed label 0) or TetGen
/// fails (its reason: self-intersecting facets, too-close facets, tiny features, out of memory...).
/// Cost: TetGen's, roughly O(n log n) in the output size; single-threaded, deterministic. Not
/// cancellable while TetGen runs (cancellation is checked between runs).
TetMesh tetrahedralize(const InterfaceComplex& plc, const TetOptions& options, Progress& progress = noProgress(),
                       TetStats* stats = nullptr);

}  // namespace jawmesh
