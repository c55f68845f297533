// The phantom as a segmentation's label volume (issue #23 item 4), so label-map input is tested
// without data files: each voxel centre takes the label of the phantom field it lies in (a tooth,
// else the bone; with PDL labels, bone within the PDL thickness of a tooth becomes that tooth's
// PDL). Labels follow io/Labels.h (bone 1 or 2, tooth 100 + UNN, PDL 200 + UNN); the segments
// carry Slicer-style names ("mandible", "tooth_24", "pdl_24") for .seg.nrrd.
#pragma once

#include "io/LabelVolume.h"
#include "io/ToothAxes.h"
#include "levelset/Phantom.h"

#include <map>
#include <string>

namespace jawmesh {

struct PhantomLabelOptions {
    double voxelMm = 0.1;
    /// > 0: label bone voxels within this distance of a tooth (mm, by the tooth's field) as its PDL.
    double pdlThicknessMm = 0;
};

/// The label volume of the phantom jaw `phantom` describes (same anatomy as makePhantom), its
/// voxel grid aligned with the axes and covering the bone with a voxel to spare; the axes known by
/// construction go to `axes` (may be null). Deterministic (TBB over slices, each voxel alone).
/// Throws Error for a voxel size outside (0, 2] mm. Cost: one field evaluation per voxel.
LabelVolume phantomLabelVolume(const PhantomOptions& phantom, const PhantomLabelOptions& options,
                               std::map<int, ToothAxes>* axes = nullptr);

}  // namespace jawmesh
