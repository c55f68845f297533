// Implements levelset/HealSocket.h; what it computes, its rules and its contract are documented there.
#include "levelset/HealSocket.h"

#include "levelset/AlveolarCrest.h"
#include "levelset/Csg.h"
#include "levelset/RewriteLevelSet.h"

#include <algorithm>
#include <cmath>

namespace jawmesh {
namespace {

/// Voxels of box whose value is negative in grid.
std::size_t insideCount(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& box) {
    auto acc = grid.getConstAccessor();
    std::size_t n = 0;
    for (auto it = box.begin(); it; ++it) n += acc.getValue(*it) < 0;
    return n;
}

}  // namespace

openvdb::FloatGrid::Ptr healSocket(const openvdb::FloatGrid& bone, const openvdb::FloatGrid& tooth, const LongAxis& axis,
                                   double gapMm, SocketFill& fill, const std::string& what) {
    fill.levelMm = crestAround(bone, tooth, axis, what).lowMm;
    const double voxel = uniformVoxelSizeMm(bone);
    const float bg = float(bandHalfWidthMm(bone));
    // The tooth's distance out past the gap: the fill is {T < gap}, its band reaches gap + bg.
    const auto reach = withExteriorReach(tooth, gapMm + bg + voxel);
    const auto& xf = bone.transform();
    auto T = reach->getConstAccessor();
    const openvdb::CoordBBox box = reach->evalActiveVoxelBoundingBox();
    // Every voxel the fill can change: within the band of its side or below its top's band.
    openvdb::MaskTree where(false);
    for (auto it = box.begin(); it; ++it)
        if (axis.heightOf(xf.indexToWorld(*it)) - fill.levelMm < bg && T.getValue(*it) - gapMm < bg) where.setValueOn(*it);
    auto healed = rewriteLevelSet(bone, std::move(where), [&]() -> VoxelValue {
        return [&, B = bone.getConstAccessor(), R = reach->getConstAccessor()](const openvdb::Coord& ijk) mutable {
            const double h = axis.heightOf(xf.indexToWorld(ijk)) - fill.levelMm;
            return std::min(B.getValue(ijk), float(std::max(double(R.getValue(ijk)) - gapMm, h)));
        };
    });
    fill.filledVolumeMm3 = double(insideCount(*healed, box) - insideCount(bone, box)) * voxel * voxel * voxel;
    return healed;
}

}  // namespace jawmesh
