// Implements levelset/SurfacesToLabelVolume.h; what it computes, its rules and its contract are documented there.
#include "levelset/SurfacesToLabelVolume.h"

#include "io/Error.h"
#include "io/LabelCase.h"
#include "io/Labels.h"
#include "levelset/JawLevelSets.h"

#include <openvdb/math/Operators.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace jawmesh {
namespace {

/// Widest gap between root and socket a segmented PDL fills (the shared mandible's cervical gaps
/// reach 0.45 mm).
constexpr double kSocketGapMm = 0.5;
/// ... where root and socket face each other within 60 degrees (cos of 120).
constexpr double kSocketFacingCos = -0.5;

/// Calls visit(ijk, value, label, accessor) for every voxel of the grid's active box that lies in
/// v, with the grid's value there, v's label to change and the thread's accessor to the grid; v's
/// voxel (i, j, k) is the grid's index (i, j, k) + offset.
template <typename Visit>
void forEachVoxelOf(LabelVolume& v, const openvdb::FloatGrid& grid, const openvdb::Coord& offset, const Visit& visit) {
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
                if (i < 0 || i >= nx) continue;
                const openvdb::Coord ijk(x, y, z);
                visit(ijk, accessor.getValue(ijk), v.values[(static_cast<std::size_t>(k) * ny + j) * nx + i], accessor);
            }
        }
    });
}

/// Writes `label` on the still unlabelled voxels of v inside `grid` (negative).
void paintInside(LabelVolume& v, const openvdb::FloatGrid& grid, const openvdb::Coord& offset, std::int32_t label) {
    forEachVoxelOf(v, grid, offset, [&](const openvdb::Coord&, float value, std::int32_t& voxel, const auto&) {
        if (value < 0 && voxel == 0) voxel = label;
    });
}

/// Whether root and socket face each other across the voxel: their distances' gradients (central
/// differences) point against each other, more than kSocketFacingCos. Not so above the bone's rim,
/// where a segmentation leaves the gingiva's space unlabelled.
template <typename ToothAccessor, typename BoneAccessor>
bool facing(const ToothAccessor& tooth, const BoneAccessor& bone, const openvdb::Coord& ijk) {
    using Gradient = openvdb::math::ISGradient<openvdb::math::CD_2ND>;
    openvdb::Vec3f t = Gradient::result(tooth, ijk), b = Gradient::result(bone, ijk);
    const float lengths = t.length() * b.length();
    return lengths > 0 && t.dot(b) < kSocketFacingCos * lengths;
}

/// Writes tooth unn's PDL label on the still unlabelled voxels within the PDL's thickness of the
/// tooth's surface inside the bone, and on those of a gap the surfaces leave between root and
/// socket (tooth and bone distances adding up to less than kSocketGapMm): a segmentation labels
/// the whole dark space between them PDL. `tooth` and `bone` are signed distances, mm.
void paintPdl(LabelVolume& v, const openvdb::FloatGrid& tooth, const openvdb::FloatGrid& bone, const openvdb::Coord& offset,
              int unn, const SegmentedPdlLabels& pdl) {
    const std::int32_t label = pdlLabel(unn);
    tbb::enumerable_thread_specific<openvdb::FloatGrid::ConstAccessor> boneAccessors(bone.getConstAccessor());
    forEachVoxelOf(v, tooth, offset, [&](const openvdb::Coord& ijk, float toothMm, std::int32_t& voxel, const auto& toothAccessor) {
        if (voxel != 0 || toothMm < 0) return;
        auto& boneAccessor = boneAccessors.local();
        const float boneMm = boneAccessor.getValue(ijk);
        if (boneMm >= 0) {
            if (toothMm + boneMm < kSocketGapMm && facing(toothAccessor, boneAccessor, ijk)) voxel = label;
            return;
        }
        if (toothMm >= pdl.maxThicknessMm) return;
        const openvdb::Vec3d p = tooth.transform().indexToWorld(ijk);
        if (toothMm < std::min(pdl.thicknessMm(Vec3(p.x(), p.y(), p.z()), unn), pdl.maxThicknessMm)) voxel = label;
    });
}

}  // namespace

LabelVolume labelVolumeFromSurfaces(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm,
                                    const SegmentedPdlLabels& pdl) {
    if (pdl.thicknessMm && !(pdl.maxThicknessMm >= 0 && pdl.maxThicknessMm <= 2))
        throw Error(jawCase.folder, "label volume: the PDL thickness bound must be in [0, 2] mm");
    // The distances must reach past the thickest PDL and across a socket's gap.
    const double bandVoxels =
        pdl.thicknessMm ? std::max(2.0, std::ceil(std::max(pdl.maxThicknessMm, kSocketGapMm) / voxelMm) + 1) : 2.0;
    const JawLevelSets sets = jawLevelSets(surfaces, jawCase, voxelMm, bandVoxels, bandVoxels, bandVoxels);
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
    // Teeth first (a voxel in a tooth and the bone is the tooth's), then the PDLs, then the bone
    // where still empty.
    for (const auto& [unn, grid] : sets.teeth) paintInside(v, *grid, box.min(), toothLabel(unn));
    if (pdl.thicknessMm)
        for (const auto& [unn, grid] : sets.teeth) paintPdl(v, *grid, *sets.bone, box.min(), unn, pdl);
    paintInside(v, *sets.bone, box.min(), bone);
    v.segments = valueSegments(v);
    nameSegmentsByLabel(v.segments, jawCase.jaw);
    return v;
}

}  // namespace jawmesh
