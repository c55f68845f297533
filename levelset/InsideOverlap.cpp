// Implements levelset/InsideOverlap.h; what it computes, its rules and its contract are documented there.
#include "levelset/InsideOverlap.h"

#include <openvdb/tools/LevelSetUtil.h>

#include <algorithm>

namespace jawmesh {

double insideOverlapFraction(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b) {
    const openvdb::CoordBBox boxA = a.evalActiveVoxelBoundingBox(), boxB = b.evalActiveVoxelBoundingBox();
    if (!boxA.hasOverlap(boxB)) return 0.0;  // the common case: teeth apart, no masks needed
    openvdb::BoolGrid::Ptr insideA = openvdb::tools::sdfInteriorMask(a);
    const openvdb::BoolGrid::Ptr insideB = openvdb::tools::sdfInteriorMask(b);
    const double volumeA = static_cast<double>(insideA->activeVoxelCount());
    const double volumeB = static_cast<double>(insideB->activeVoxelCount());
    const double smaller = std::min(volumeA, volumeB);
    if (smaller <= 0) return 0.0;
    insideA->topologyIntersection(*insideB);
    return static_cast<double>(insideA->activeVoxelCount()) / smaller;
}

}  // namespace jawmesh
