// Planar cross-sections of a labeled tet mesh as label images, and where the report cuts: through
// each tooth along its long axis (buccolingual, so the PDL shows on both sides of the root and the
// crest cap at the top) and through the arch at the height of the PDLs (every root ring at once).
// Element edges are kept as a mask, so the pictures also show the mesh grading.
#pragma once

#include "io/TetMesh.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace jawmesh {

/// A rectangle in space: centre, two orthonormal in-plane directions, size (mm).
struct SectionPlane {
    Vec3 centreMm = Vec3::Zero();
    Vec3 right = Vec3::UnitX();  ///< image x
    Vec3 up = Vec3::UnitY();     ///< image y (rows go down, so up points to row 0)
    double widthMm = 1, heightMm = 1;
};

/// Label of each pixel of a section (row-major, row 0 at the top), kOutsideLabel where no tet.
struct SectionRaster {
    int width = 0, height = 0;
    double pixelMm = 0;
    std::vector<Label> label;
    std::vector<std::uint8_t> edge;  ///< 1 where an element edge of the section crosses the pixel
};

/// Rasterises the section of `mesh` by `plane`: a pixel takes the label of the tet whose section
/// polygon holds the pixel centre (the later tet on a shared edge). pixelMm > 0; the image has
/// ceil(width / pixelMm) x ceil(height / pixelMm) pixels (at most 4096 a side).
/// Deterministic (serial per section). Throws Error for a non-positive pixel size or a plane whose
/// directions are not orthonormal. Cost: O(T) plus the pixels covered.
SectionRaster rasterizeSection(const TetMesh& mesh, const SectionPlane& plane, double pixelMm);

/// Buccolingual plane through tooth `unn`: contains its long axis (principal axis of largest
/// spread of its tets' volume, `up` pointing away from its PDL, i.e. occlusally) and is
/// perpendicular to the arch there (the arch tangent runs from the previous to the next tooth in
/// UNN order; with one tooth, the plane takes the tooth's axis of smallest spread). Sized 1.3 x the
/// tooth length, 0.8 x as wide. Cost: a pass over the tets per tooth of the mesh.
/// Returns nothing when the mesh has no tets of that tooth.
std::optional<SectionPlane> toothSectionPlane(const TetMesh& mesh, int unn);

/// Plane across the whole arch: normal along the mean long axis of the teeth, through the volume
/// centroid of the PDL tets (of the teeth when there is no PDL; of everything when there is no
/// tooth), `right` along the arch's widest spread; sized to the mesh's projection plus 5%.
/// Returns nothing for an empty mesh.
std::optional<SectionPlane> archSectionPlane(const TetMesh& mesh);

}  // namespace jawmesh
