// Local rewrites of a level set, the step under every edit of the jaw (levelset/JawEdits.h): new
// values on every voxel an edit can change, inside and outside alike, so that what the new values
// enclose becomes inside (a healed socket) and what they cut off becomes outside (a lowered crest).
// Every voxel whose sign may change must be in the rewritten set: signs are not re-derived by a
// flood fill. (They were, first: OpenVDB's signed flood fill carries a sign along z through
// leaves and tiles without active voxels, and a band left incomplete by an edit grew a column of
// bone 0.4 mm wide and 2 mm tall beside a crown of the shared mandible.)
#pragma once

#include <openvdb/openvdb.h>

#include <functional>

namespace jawmesh {

/// The value (mm) of the edited level set at a voxel. One is made per thread (it may hold accessors).
using VoxelValue = std::function<float(const openvdb::Coord&)>;

/// A copy of `grid` (a level set, mm) holding, on every voxel of `where` (tiles included), the value
/// a VoxelValue from makeValue() gives: active when within the band, else the background with its
/// sign; every other voxel as it was. Throws Error for a grid that is not a level set.
/// Cost: |where| evaluations in parallel, a serial merge of the changed voxels, a prune.
openvdb::FloatGrid::Ptr rewriteLevelSet(const openvdb::FloatGrid& grid, openvdb::MaskTree where,
                                        const std::function<VoxelValue()>& makeValue);

}  // namespace jawmesh
