// TetGen input files for an InterfaceComplex: .poly / .smesh (nodes, triangular facets with a
// boundary marker interfaceMarker (io/InterfaceComplex.h) of the label pair:
// 1024 * min label + max label), the region list from the seeds, plus each region's boundary
// as its own surface file for inspection.
#pragma once

#include "io/InterfaceComplex.h"

#include <string>

namespace jawmesh {

/// Writes `complex` for TetGen: ".poly" (part 1 nodes, part 2 one single-polygon facet per
/// triangle with its marker (1024 * min label + max label), oriented with its normal into the lower
/// label (io/PolyReader.h reads the sides back from that), part 3 no holes, part 4 one region per seed: point and label as the
/// region attribute, no volume constraint) or ".smesh" (same content, the smesh layout), chosen by
/// the extension. Indices are 1-based. Written atomically.
/// Throws Error on I/O failure, another extension, or sides / triangles of different lengths.
void writeTetgenPoly(const InterfaceComplex& complex, const std::string& path);

/// Writes one surface per region label in `complex` (outside excepted) to
/// "<folder>/<labelName>.<ext>" (ext "ply", "stl" or "obj"): the triangles bounding the region,
/// oriented outward from it, with unused vertices dropped. Throws Error on I/O failure.
void writeRegionBoundaries(const InterfaceComplex& complex, const std::string& folder,
                           const std::string& ext = "ply");

/// The boundary of region `label` in `complex`, oriented outward, unused vertices dropped.
SurfaceMesh regionBoundary(const InterfaceComplex& complex, Label label);

}  // namespace jawmesh
