// Thin plates of a region: where two nearly parallel sheets bound a region from both sides closer
// than a tenth of a millimetre (a bone lip at the alveolar crest, a PDL pinched between two roots).
//
// Why: the tets filling a plate of thickness T between triangles of edge L have dihedral angles of
// about atan(T / L). Simplification must neither thin a plate (each sheet may move by its whole
// error bound, towards the other) nor put long edges on it; filters/SimplifyInterfaces.h bounds
// both by the plate thickness measured here on the fine surface. On the shared mandible, plates of
// 0.02-0.05 mm at the crest had been thinned to 0.002-0.004 mm, where the worst tets were.
//
// Measure: from each vertex, along the normal of each interface through it, into each region on
// either side (never the outside), the distance to the first triangle hit, when that triangle
// bounds the same region and faces the vertex (the normal of that sheet around the hit, into the
// region, within maxAngleDeg of the way back). A wedge at a junction curve (sheets meeting at a
// wider angle) is not a plate.
#pragma once

#include "io/InterfaceComplex.h"

#include <vector>

namespace jawmesh {

struct PlateOptions {
    double maxMm = 0.1;         ///< thicker is not a plate (the result is +inf there), mm
    double maxAngleDeg = 30.0;  ///< largest angle between the two sheets of a plate
};

/// Per vertex of `complex`: the thickness of the thinnest plate it bounds, mm; +inf where it bounds
/// none or where `measure` (per vertex, may be empty = all) is 0. Deterministic (a pure function
/// of the geometry), parallel over slabs along x. Cost: O(n log n) in the triangles; memory about
/// 24 bytes per triangle of one slab at a time per thread.
std::vector<float> plateThicknessMm(const InterfaceComplex& complex, const std::vector<char>& measure,
                                    const PlateOptions& options = {});

}  // namespace jawmesh
