// Labels of TetGen's tets read from the interface sides rather than from its seed flooding, and
// the tets no region claims dropped: the step between tet/TetgenAdapter.h's raw output and a
// labeled mesh of the regions alone.
#pragma once

#include "io/InterfaceComplex.h"
#include "tet/TetgenAdapter.h"

#include <cstddef>

namespace jawmesh {

/// With the boundary preserved (-Y) every input triangle is a tet face, so the tets split into
/// components separated only by input triangles (or the pieces of one TetGen had to split), and
/// each whole input triangle says which label lies on which side (its normal points into
/// sides[0]). Sets raw.mesh.labels from that, not from TetGen's seed flooding: a seed a rounding
/// error away from a thin region's facet (a PDL fragment at the crest, seen on the shared mandible)
/// would otherwise label the region wrongly. Tets of components on the outside side are labeled
/// kOutsideLabel. `plc` is the complex TetGen was given.
/// Throws Error when a component's sides disagree (an open region boundary: TetGen lost a facet)
/// or a component touches no input triangle (a hull region TetGen kept).
void labelFromSides(const InterfaceComplex& plc, TetgenMesh& raw);

/// Drops the tets labeled kOutsideLabel and the nodes no other tet uses, keeping the order of
/// both. Returns the number of tets dropped.
std::size_t keepLabeled(TetMesh& mesh);

}  // namespace jawmesh
