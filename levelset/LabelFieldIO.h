// A LabelField as .vdb files in one folder, so a run can stop after carving, a user can edit a
// level set (e.g. in Houdini or with OpenVDB's tools) and the pipeline can resume from it:
//   <dir>/labels.vdb            Int32 label grid (metadata: "jaw", "voxel_size_mm")
//   <dir>/<labelName(L)>.vdb    FloatGrid level set of region L (metadata "label" = L), e.g.
//                               bone_mandible.vdb, tooth_24.vdb, pdl_24.vdb
#pragma once

#include "levelset/LabelField.h"

#include <string>

namespace jawmesh {

/// Writes every grid of the field into dir (created if missing), each file atomically.
/// Throws Error for a field without labels or on I/O failure.
/// Cost: proportional to the active voxels; files are written uncompressed-by-default OpenVDB (zip).
void writeLabelField(const LabelField& field, const std::string& dir);

/// Reads a folder written by writeLabelField (or edited since): labels.vdb and every other *.vdb
/// holding a FloatGrid with a "label" metadata entry. Throws Error naming the file when labels.vdb
/// is missing or unreadable, a grid has the wrong type, or transforms differ.
LabelField readLabelField(const std::string& dir);

}  // namespace jawmesh
