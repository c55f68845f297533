// How much two closed domains share, from their level sets: a segmentation that exported one tooth
// twice, or two teeth grown into each other, shows as a large shared volume. Small overlaps (teeth
// in contact) are normal and are split by the carving (levelset/CarveGaps.h).
#pragma once

#include <openvdb/openvdb.h>

namespace jawmesh {

/// Share of the smaller tooth's volume two teeth may have in common before a case is refused:
/// teeth in contact share a few percent (the shared real teeth stay below it, tested in
/// tests/levelset/slow_inside_overlap.cpp); a tooth exported twice shares nearly all of it.
constexpr double kHeavyToothOverlapFraction = 0.3;

/// Volume inside both a and b over the smaller of the two inside volumes, in [0, 1] (0 when
/// either is empty). Inside is value < 0, inactive voxels and tiles included (sign of their value).
/// Both grids must share one transform (the same voxel size). Cost: two interior masks, tile-aware.
double insideOverlapFraction(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b);

}  // namespace jawmesh
