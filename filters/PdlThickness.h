// PDL thickness as the evaluation reports it: at every point of the PDL's tooth-side interface
// (faces between tooth_i and pdl_i), the distance to the nearest point of its bone-side interface
// (faces between pdl_i and bone). Where the PDL ends at the crest cap the tooth side continues
// until the cap, so the cap shows as the thicker tail of the distribution.
#pragma once

#include "filters/SurfaceDistance.h"

namespace jawmesh {

/// Thickness distribution of one PDL and its samples (for histograms over the jaw).
struct PdlThickness {
    DistanceSummary summary;  ///< area-weighted over the tooth-side interface; max refined
    DistanceSamples samples;  ///< thickness samples on the tooth side
};

/// Thickness of the PDL between `toothSide` and `boneSide` (both non-empty), sampled every
/// spacingMm, max exact to toleranceMm. Throws Error when either interface is empty, Cancelled.
/// Cost: one BVH over boneSide plus a query per sample.
PdlThickness pdlThickness(const SurfaceMesh& toothSide, const SurfaceMesh& boneSide, double spacingMm,
                          double toleranceMm, Progress& progress = noProgress());

}  // namespace jawmesh
