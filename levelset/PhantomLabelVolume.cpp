// Implements levelset/PhantomLabelVolume.h; what it computes, its rules and its contract are documented there.
#include "levelset/PhantomLabelVolume.h"

#include "io/Error.h"
#include "io/LabelCase.h"
#include "io/Labels.h"
#include "levelset/PhantomAnatomy.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>

namespace jawmesh {
namespace {

/// The label at a template-frame point: the first tooth whose field is negative, else bone, PDL
/// or outside. `arch`: the arch position of p's vertical line, found here when first needed.
std::int32_t labelAt(const phantom::JawAnatomy& an, const Vec3& p, double pdlMm, std::optional<phantom::ArchPosition>& arch) {
    const bool inBody = an.boneBox.min.x() <= p.x() && p.x() <= an.boneBox.max.x() && an.boneBox.min.y() <= p.y() &&
                        p.y() <= an.boneBox.max.y() && an.boneBox.min.z() <= p.z() && p.z() <= an.boneBox.max.z();
    int nearTooth = 0;
    for (const phantom::ToothSpec& t : an.teeth) {
        if ((p.array() < t.box.min.array() - pdlMm).any() || (p.array() > t.box.max.array() + pdlMm).any()) continue;
        const double f = phantom::toothField(t, p);
        if (f < 0) return toothLabel(t.unn);
        if (pdlMm > 0 && f < pdlMm && nearTooth == 0) nearTooth = t.unn;
    }
    if (!inBody) return kOutsideLabel;
    if (!arch) arch = an.arch.closest(p);
    if (phantom::boneField(an, p, *arch) >= 0) return kOutsideLabel;
    if (nearTooth) return pdlLabel(nearTooth);
    return an.jaw == Jaw::Mandible ? kMandibleBoneLabel : kMaxillaBoneLabel;
}

}  // namespace

LabelVolume phantomLabelVolume(const PhantomOptions& phantom, const PhantomLabelOptions& o, std::map<int, ToothAxes>* axes) {
    if (!(o.voxelMm > 0 && o.voxelMm <= 2)) throw Error("phantom label volume: voxel size must be in (0, 2] mm");
    const phantom::JawAnatomy an = phantom::buildJawAnatomy(phantom.jaw, phantom.teeth, phantom.seed);
    BBox box = phantom::toWorld(an, an.boneBox);
    for (const phantom::ToothSpec& t : an.teeth) {
        const BBox b = phantom::toWorld(an, t.box);
        box.min = box.min.cwiseMin(b.min), box.max = box.max.cwiseMax(b.max);
    }
    LabelVolume v;
    v.path = "phantom label volume";
    for (int a = 0; a < 3; ++a)
        v.size[static_cast<std::size_t>(a)] = static_cast<int>(std::ceil((box.max[a] - box.min[a]) / o.voxelMm)) + 3;
    v.directionsMm = Eigen::Matrix3d::Identity() * o.voxelMm;
    // On whole voxels from the world origin: a round voxel size then keeps every coordinate exact
    // in NIfTI-1's single-precision sform, so every format gives the same volume.
    v.originMm = ((box.min / o.voxelMm).array().floor() - 1.0).matrix() * o.voxelMm;
    v.values.assign(v.voxels(), 0);
    const std::size_t nx = static_cast<std::size_t>(v.size[0]), ny = static_cast<std::size_t>(v.size[1]);
    // by vertical lines (the volume's axes are the template's, which differs from the world in z
    // only): the arch is asked once per line
    tbb::parallel_for(std::size_t(0), ny, [&](std::size_t j) {
        for (std::size_t i = 0; i < nx; ++i) {
            std::optional<phantom::ArchPosition> arch;
            for (int k = 0; k < v.size[2]; ++k) {
                const Vec3 world = v.worldOf(static_cast<double>(i), static_cast<double>(j), k);
                v.values[(static_cast<std::size_t>(k) * ny + j) * nx + i] =
                    labelAt(an, phantom::toTemplate(an, world), o.pdlThicknessMm, arch);
            }
        }
    });
    v.segments = valueSegments(v);
    nameSegmentsByLabel(v.segments, an.jaw);
    if (axes)
        for (const phantom::ToothSpec& t : an.teeth) (*axes)[t.unn] = phantom::toothAxes(an, t);
    return v;
}

}  // namespace jawmesh
