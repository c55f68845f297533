// Writes a jaw given as a label volume in the case layout (io/Case.h): the volume, labels.json
// naming its labels and the axes, for the phantom's and the tests' label-map cases.
#pragma once

#include "io/LabelVolume.h"
#include "io/Labels.h"
#include "io/ToothAxes.h"

#include <map>
#include <string>

namespace jawmesh {

/// Names segments as io/Labels.h reads their values: the jaw's name for bone, "tooth_<UNN>",
/// "pdl_<UNN>" (what 3D Slicer users call them, and what labels.json maps them to).
void nameSegmentsByLabel(std::vector<LabelSegment>& segments, Jaw jaw);

/// Writes <caseDir>/input/<jaw>/<fileName> (labels.nrrd, labels.seg.nrrd with the segments'
/// names as 3D Slicer keeps them, labels.nii or labels.nii.gz), labels.json mapping every
/// segment's value to its role by its name (not for .seg.nrrd: its names say it) and, when `axes`
/// is not empty, teeth_axes_<jaw>.json. Atomic per file. Throws Error naming the file.
void writeLabelCase(const LabelVolume& volume, Jaw jaw, const std::map<int, ToothAxes>& axes, const std::string& caseDir,
                    const std::string& fileName);

}  // namespace jawmesh
