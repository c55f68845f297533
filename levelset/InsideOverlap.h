// How much two closed domains share, from their level sets: a segmentation that exported one tooth
// twice, or two teeth grown into each other, shows as a large shared volume. Small overlaps (teeth
// in contact) are normal and are split by the carving (levelset/CarveGaps.h).
#pragma once

#include <openvdb/openvdb.h>

namespace jawmesh {

/// Volume inside both a and b over the smaller of the two inside volumes, in [0, 1] (0 when
/// either is empty). Inside is value < 0, inactive voxels and tiles included (sign of their value).
/// Both grids must share one transform (the same voxel size). Cost: two interior masks, tile-aware.
double insideOverlapFraction(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b);

}  // namespace jawmesh
