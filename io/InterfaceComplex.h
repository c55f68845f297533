// The multi-material interface surface: a piecewise-linear complex in which every interface between
// two regions appears once and is shared by both. Output of filters/ (extraction + simplification),
// input of tet/ (TetGen). Labels as in io/Labels.h; kOutsideLabel (0) is the outside.
#pragma once

#include "io/Labels.h"
#include "io/SurfaceMesh.h"

#include <array>
#include <vector>

namespace jawmesh {

struct RegionSeed {
    Vec3 point;    ///< a point strictly inside one connected component of the region, mm
    Label label;   ///< the region's label (never kOutsideLabel)
};

/// Facet marker encoding the label pair of an interface triangle (TetGen .poly files, Medit
/// references): lo * 1024 + hi with lo < hi, so it is > 0 and unique for every pair of labels.
int interfaceMarker(Label a, Label b);
/// Inverse of interfaceMarker: {lo, hi}.
std::array<Label, 2> interfacePairFromMarker(int marker);

struct InterfaceComplex {
    SurfaceMesh surface;  ///< all interface triangles, vertices shared between interfaces
    /// Per triangle, the two labels it separates: the triangle's normal (right-hand rule) points
    /// into sides[t][0] and out of sides[t][1]. sides[t][0] != sides[t][1].
    std::vector<std::array<Label, 2>> sides;
    std::vector<RegionSeed> seeds;  ///< one per connected component of every region
    /// Optional, from the adaptive extraction (filters/AdaptiveCells.h), consumed by the
    /// simplification; empty otherwise. Per triangle: vertices of the fine interface that it stands
    /// for, which are corners of no triangle (they follow all corners in surface.vertices; use
    /// withoutCarried before handing the complex to anything else). Per corner vertex: how far the
    /// sample points of the triangles around it may already be from the fine interface, mm.
    std::vector<std::vector<std::int32_t>> carried;
    std::vector<float> sampleErrorMm;
};

/// The complex without its carried vertices (the corners only, same order) and without the
/// adaptive extraction's data: what a writer or TetGen may see.
InterfaceComplex withoutCarried(InterfaceComplex complex);

}  // namespace jawmesh
