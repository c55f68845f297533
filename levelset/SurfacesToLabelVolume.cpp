// Implements levelset/SurfacesToLabelVolume.h; what it computes, its rules and its contract are documented there.
#include "levelset/SurfacesToLabelVolume.h"

#include "io/LabelCase.h"
#include "io/Labels.h"
#include "levelset/JawLevelSets.h"

#include <tbb/parallel_for.h>


namespace jawmesh {
namespace {

/// Writes `label` on the voxels of `v` inside `grid` (negative) within the grid's active box,
/// where `writable` allows; v's voxel (i, j, k) is the grid's index (i, j, k) + offset.
void paint(LabelVolume& v, const openvdb::FloatGrid& grid, const openvdb::Coord& offset, std::int32_t label,
           const std::function<bool(std::int32_t)>& writable) {
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    const int nx = v.size[0], ny = v.size[1];
    tbb::parallel_for(box.min().z(), box.max().z() + 1, [&](int z) {
        auto accessor = grid.getConstAccessor();
        const int k = z - offset.z();
        if (k < 0 || k >= v.size[2]) return;
        for (int y = box.min().y(); y <= box.max().y(); ++y) {
            const int j = y - offset.y();
            if (j < 0 || j >= ny) continue;
            for (int x = box.min().x(); x <= box.max().x(); ++x) {
                const int i = x - offset.x();
                if (i < 0 || i >= nx || !(accessor.getValue({x, y, z}) < 0)) continue;
                std::int32_t& value = v.values[(static_cast<std::size_t>(k) * ny + j) * nx + i];
                if (writable(value)) value = label;
            }
        }
    });
}

}  // namespace

LabelVolume labelVolumeFromSurfaces(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm) {
    const JawLevelSets sets = jawLevelSets(surfaces, jawCase, voxelMm, 2.0, 2.0);
    openvdb::CoordBBox box = sets.bone->evalActiveVoxelBoundingBox();
    for (const auto& [unn, grid] : sets.teeth) box.expand(grid->evalActiveVoxelBoundingBox());
    box.expand(1);
    LabelVolume v;
    v.path = jawCase.folder;
    v.size = {box.dim().x(), box.dim().y(), box.dim().z()};
    const openvdb::Vec3d origin = sets.bone->transform().indexToWorld(box.min());
    v.originMm = Vec3(origin.x(), origin.y(), origin.z());
    v.directionsMm = Eigen::Matrix3d::Identity() * sets.bone->voxelSize().x();
    v.values.assign(v.voxels(), 0);
    const std::int32_t bone = jawCase.jaw == Jaw::Mandible ? kMandibleBoneLabel : kMaxillaBoneLabel;
    // Teeth first (a voxel in a tooth and the bone is the tooth's), then the bone where still empty.
    for (const auto& [unn, grid] : sets.teeth)
        paint(v, *grid, box.min(), toothLabel(unn), [](std::int32_t value) { return value == 0; });
    paint(v, *sets.bone, box.min(), bone, [](std::int32_t value) { return value == 0; });
    v.segments = valueSegments(v);
    nameSegmentsByLabel(v.segments, jawCase.jaw);
    return v;
}

}  // namespace jawmesh
