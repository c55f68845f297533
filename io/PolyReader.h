// Reads back the TetGen .poly files of io/PolyWriter.h: the interface complex a failed run keeps
// in failed_surface/, so the tet stage can be replayed on it (bench_retet, tests).
#pragma once

#include "io/InterfaceComplex.h"

#include <string>

namespace jawmesh {

/// Reads a .poly written by writeTetgenPoly: nodes, single-triangle facets whose marker is
/// interfaceMarker of the label pair, no holes, one region per seed (its attribute the label).
/// The file keeps the pair, not its order: sides are read as {lower label, higher label}, the
/// triangle's normal pointing into the lower one, which is how writeTetgenPoly orients them.
/// Throws Error on a malformed file (counts, indices out of range, facets that are not one triangle).
InterfaceComplex readTetgenPoly(const std::string& path);

}  // namespace jawmesh
