// The evaluation of a labeled jaw mesh that `jawmesh eval` and every run report (report.json):
// conformity counts, per-label sizes, element quality per region with histograms, two-sided
// distances from each output region surface to its input surface split into crown and root, PDL
// thickness per tooth and over the jaw, and a verdict. Metrics come from tet/ (validation, quality,
// region boundaries) and filters/ (distances, PDL thickness, distributions); this file only
// decides what is measured against what, and the JSON layout (docs/DESIGN.md, "Evaluation").
//
// Crown and root (the alveolar crest): a tooth's output surface is split by what lies across each
// face. Faces against its PDL or the bone are root; faces against the outside (or another tooth)
// are crown; the crest is the curve where the two meet, i.e. where the tooth surface meets bone or
// PDL. Crown faces with a corner within cervicalBandMm of a root face are the cervical band, a part
// of its own: there the carve's root erosion begins (the root is pulled in by the PDL's inner
// share, about 0.1 mm, and a smooth cap joins it to the kept crown), so the crown's own figure is
// the crown above the band. An input tooth triangle takes the part of the output tooth face nearest
// to it (at its first area sample). The bone is split the same way: "outer" faces the outside, "socket" faces a PDL
// or a tooth.
#pragma once

#include "io/Case.h"
#include "io/Progress.h"
#include "io/TetMesh.h"

#include <nlohmann/json.hpp>

#include <map>

namespace jawmesh {

struct EvalOptions {
    double sampleSpacingMm = 0.2;        ///< area samples for means and percentiles (filters/SurfaceDistance.h)
    double hausdorffToleranceMm = 0.002; ///< maxima exact to this (well below the 0.05 mm voxel)
    double pdlTargetMm = 0.2;            ///< the PDL check: p05 and p95 within target +- tolerance (0: no target, measured only)
    double pdlToleranceMm = 0.03;
    std::map<int, double> toothPdlTargetMm; ///< a tooth's own target (an edited PDL; 0: measured only)
    double crownToleranceMm = 0.05;      ///< the crown check: two-sided crown Hausdorff at most this
    double cervicalBandMm = 0.5;         ///< crown faces this near the root faces: the cervical band
    double minDihedralDeg = 10.0;        ///< the quality check
    int histogramBins = 40;
    nlohmann::json edits;                ///< the run's edits as run.json records them, copied into the report
};

/// Measures `mesh` and, when `input` is given (the jaw's input surfaces), its distance to them.
/// Returns report.json's content: keys "schema", "verdict", "mesh", "validation", "sizes",
/// "regions", "quality", "distance" (null without input), "pdl_thickness", "options", "seconds".
/// A structurally broken mesh (indices out of range, unknown labels) gets the validation part and
/// a failing verdict only. Never throws for a bad mesh; throws Error when `input` does not overlap
/// the mesh (bounding boxes sharing less than half the smaller one: a wrong input folder), Cancelled.
/// Deterministic for any thread count. Cost: validation and face adjacency O(T log T), quality
/// O(T), distances one BVH query per area sample (a few seconds for a 1 M-tet jaw against a
/// 1.7 M-triangle input on two cores).
nlohmann::json evaluateMesh(const TetMesh& mesh, const JawSurfaces* input, const EvalOptions& options = {},
                            Progress& progress = noProgress());

}  // namespace jawmesh
