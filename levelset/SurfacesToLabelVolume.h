// A jaw's surfaces as a segmentation's label volume: what a user's label map of the same anatomy
// would hold, so the label-map input can be tested and timed on real anatomy (issue #23 item 4).
// Each voxel centre takes the label of the first tooth whose surface holds it (UNN order), else
// the bone's, else 0; inside is decided by the pipeline's own level sets (winding, dirty input).
#pragma once

#include "io/Case.h"
#include "io/LabelVolume.h"

namespace jawmesh {

/// The label volume of `surfaces` on an axis-aligned grid of `voxelMm` covering the bone with a
/// voxel to spare; labels as io/Labels.h (bone 1 or 2, tooth 100 + UNN), segments named "mandible"
/// or "maxilla" and "tooth_<UNN>". Throws as jawLevelSets. Cost: one level-set lookup per voxel of
/// the bone's box plus one per voxel of each tooth's box (TBB over slices).
LabelVolume labelVolumeFromSurfaces(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm);

}  // namespace jawmesh
