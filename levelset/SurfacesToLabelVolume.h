// A jaw's surfaces as a segmentation's label volume: what a user's label map of the same anatomy
// would hold, so the label-map input can be tested and timed on real anatomy (issue #23 item 4).
// Each voxel centre takes the label of the first tooth whose surface holds it (UNN order), else
// (when asked) the PDL label of the first tooth within its PDL's thickness, else the bone's, else
// 0; inside is decided by the pipeline's own level sets (winding, dirty input).
#pragma once

#include "io/Case.h"
#include "io/LabelVolume.h"

#include <functional>

namespace jawmesh {

/// Segmented PDLs, as a segmentation that labels the socket's gap leaves them: a voxel centre
/// outside every tooth, inside the bone and within `thicknessMm(centre, unn)` of tooth unn's
/// surface is that tooth's PDL (pdl_<UNN>), and so is one in a gap the surfaces leave between
/// root and socket (its distances to both adding up to less than 0.5 mm, their surfaces facing each
/// other: not above the bone's rim). The thickness may vary
/// from point to point (uneven PDLs); it must not exceed maxThicknessMm.
struct SegmentedPdlLabels {
    std::function<double(const Vec3& pointMm, int unn)> thicknessMm;  ///< empty: no PDL labels
    double maxThicknessMm = 0;
};

/// The label volume of `surfaces` on an axis-aligned grid of `voxelMm` covering the bone with a
/// voxel to spare; labels as io/Labels.h (bone 1 or 2, tooth 100 + UNN, PDL 200 + UNN), segments
/// named "mandible" or "maxilla", "tooth_<UNN>" and "pdl_<UNN>". Throws as jawLevelSets, and Error
/// for a PDL thickness bound outside [0, 2] mm. Cost: one level-set lookup per voxel of the bone's
/// box plus one per voxel of each tooth's box (TBB over slices).
LabelVolume labelVolumeFromSurfaces(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm,
                                    const SegmentedPdlLabels& pdl = {});

}  // namespace jawmesh
