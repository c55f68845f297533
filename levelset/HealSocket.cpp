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
    auto B = bone.getConstAccessor();
    const openvdb::CoordBBox box = reach->evalActiveVoxelBoundingBox();
    // The fill's band (its side and its top) and the bone's band inside it.
    openvdb::MaskTree where(false);
    for (auto it = box.begin(); it; ++it) {
        const double h = axis.heightOf(xf.indexToWorld(*it)) - fill.levelMm;
        if (h > bg + voxel) continue;
        const double g = T.getValue(*it) - gapMm;
        if (g > bg) continue;
        if (std::abs(h) <= bg + voxel || g > -bg || B.isValueOn(*it)) where.setValueOn(*it);
    }
    const auto& boneTree = bone.tree();
    const auto& toothTree = reach->tree();
    auto healed = rewriteLevelSet(bone, where, [&](const openvdb::Coord& ijk) {
        const double h = axis.heightOf(xf.indexToWorld(ijk)) - fill.levelMm;
        return std::min(boneTree.getValue(ijk), float(std::max(double(toothTree.getValue(ijk)) - gapMm, h)));
    });
    fill.filledVolumeMm3 = double(insideCount(*healed, box) - insideCount(bone, box)) * voxel * voxel * voxel;
    return healed;
}

}  // namespace jawmesh
