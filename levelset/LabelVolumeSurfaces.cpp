// Implements levelset/LabelVolumeSurfaces.h; what it computes, its rules and its contract are documented there.
#include "levelset/LabelVolumeSurfaces.h"

#include "io/Error.h"
#include "io/ParallelInOrder.h"
#include "levelset/LevelSetSurface.h"

#include <openvdb/tools/ChangeBackground.h>
#include <openvdb/tools/Filter.h>
#include <openvdb/tools/TopologyToLevelSet.h>
#include <openvdb/tree/LeafManager.h>

#include <algorithm>
#include <map>

namespace jawmesh {
namespace {

/// The voxels of each group of segments as an index-space mask (voxel (i, j, k) at index (i, j, k)),
/// all in one pass over the volume: a jaw's 15-30 roles would otherwise read it 15-30 times.
std::vector<openvdb::MaskGrid::Ptr> segmentMasks(const LabelVolume& v, const std::vector<std::vector<std::size_t>>& groups) {
    std::map<int, std::map<std::int32_t, std::vector<std::size_t>>> groupsOf;  // layer -> value -> groups
    for (std::size_t g = 0; g < groups.size(); ++g)
        for (std::size_t s : groups[g]) groupsOf[v.segments[s].layer][v.segments[s].value].push_back(g);
    std::vector<openvdb::MaskGrid::Ptr> masks;
    std::vector<openvdb::MaskGrid::Accessor> accessors;
    for (std::size_t g = 0; g < groups.size(); ++g) {
        masks.push_back(openvdb::MaskGrid::create());
        accessors.push_back(masks.back()->getAccessor());
    }
    const std::size_t nx = static_cast<std::size_t>(v.size[0]), nxy = nx * static_cast<std::size_t>(v.size[1]);
    static const std::vector<std::size_t> none;
    for (const auto& [layer, byValue] : groupsOf) {
        const std::int32_t* data = v.values.data() + static_cast<std::size_t>(layer) * v.voxels();
        std::int32_t last = 0;
        const std::vector<std::size_t>* lastGroups = &none;  // labels come in runs: look each run up once
        for (std::size_t i = 0; i < v.voxels(); ++i) {
            const std::int32_t x = data[i];
            if (x == 0) continue;
            if (x != last) {
                const auto it = byValue.find(x);
                last = x, lastGroups = it == byValue.end() ? &none : &it->second;
            }
            for (std::size_t g : *lastGroups)
                accessors[g].setValueOn(openvdb::Coord(static_cast<int>(i % nx), static_cast<int>((i % nxy) / nx), static_cast<int>(i / nxy)));
        }
    }
    return masks;
}

constexpr float kMarginVoxels = 0.1f;  // voxel centres keep at least this far on their side

/// The voxels' indicator as a narrow-band grid in voxel index space: -0.5 inside, +0.5 outside
/// (a flat face then crosses zero exactly on the voxel faces), 3 voxels each side active.
openvdb::FloatGrid::Ptr indicatorOf(const openvdb::MaskGrid& mask) {
    openvdb::FloatGrid::Ptr grid = openvdb::tools::topologyToLevelSet(mask, 3, 0, 0, 0);  // for its band
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid->tree());
    leaves.foreach([&](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
        openvdb::tree::ValueAccessor<const openvdb::MaskTree> inside(mask.tree());
        for (auto it = leaf.beginValueOn(); it; ++it) it.setValue(inside.isValueOn(it.getCoord()) ? -0.5f : 0.5f);
    });
    openvdb::tools::changeLevelSetBackground(grid->tree(), 0.5f);
    return grid;
}

/// Constrained smoothing of a binary volume (after Whitaker 2000, "Reducing aliasing artifacts
/// in iso-surfaces of binary volumes"): box means of the indicator, each followed by putting every
/// voxel centre back on its own side by the margin. The staircase goes and the surface never
/// crosses a voxel centre, so it stays within a voxel of the label boundary.
void smoothWithinVoxels(openvdb::FloatGrid& grid, const openvdb::MaskGrid& mask, int steps) {
    openvdb::tools::Filter<openvdb::FloatGrid> filter(grid);
    for (int n = 0; n < steps; ++n) {
        filter.mean(1);
        openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
        leaves.foreach([&](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
            openvdb::tree::ValueAccessor<const openvdb::MaskTree> inside(mask.tree());
            for (auto it = leaf.beginValueOn(); it; ++it) {
                if (inside.isValueOn(it.getCoord())) it.setValue(std::min(*it, -kMarginVoxels));
                else it.setValue(std::max(*it, kMarginVoxels));
            }
        });
    }
}

/// The iso value whose surface encloses the voxels' volume: smoothing rounds convex parts inward
/// (2 steps: 3.5-5 % of a 3 mm ball or a 7-voxel slab), so one secant step on the volume moves the
/// surface back out; kept inside the margin so no voxel centre changes side. Volumes in voxels.
double volumeMatchingIso(const openvdb::FloatGrid& grid, double voxels) {
    constexpr double kProbe = 0.02;
    const double atZero = signedVolume(extractLevelSetSurface(grid, 0.0));
    const double atProbe = signedVolume(extractLevelSetSurface(grid, kProbe));
    if (!(atProbe > atZero)) return 0.0;
    const double iso = kProbe * (voxels - atZero) / (atProbe - atZero);
    return std::clamp(iso, -0.9 * kMarginVoxels, 0.9 * kMarginVoxels);
}

/// The surface of the voxels of `mask` (see labelSurface), in world millimetres; at iso 0 unless
/// `matchVolume` (surfacesFromLabelVolume says when not).
SurfaceMesh maskSurface(const LabelVolume& v, const openvdb::MaskGrid& mask, int smoothingSteps, bool matchVolume) {
    if (mask.activeVoxelCount() == 0) throw Error(v.path, "a role has no voxel");
    // No closing or dilation: it would merge what the segmentation kept apart.
    const openvdb::FloatGrid::Ptr indicator = indicatorOf(mask);
    smoothWithinVoxels(*indicator, mask, smoothingSteps);
    const double iso = matchVolume ? volumeMatchingIso(*indicator, static_cast<double>(mask.activeVoxelCount())) : 0.0;
    SurfaceMesh surface = extractLevelSetSurface(*indicator, iso);
    for (Vec3& p : surface.vertices) p = v.worldOf(p.x(), p.y(), p.z());
    // An index-to-world map that mirrors (negative determinant) turns the winding inside out.
    if (signedVolume(surface) < 0)
        for (Tri& t : surface.triangles) std::swap(t[1], t[2]);
    return surface;
}

}  // namespace

SurfaceMesh labelSurface(const LabelVolume& v, const std::vector<std::size_t>& segments, int smoothingSteps) {
    return maskSurface(v, *segmentMasks(v, {segments}).front(), smoothingSteps, true);
}

JawSurfaces surfacesFromLabelVolume(LabelVolume&& v, const LabelAssignment& roles, Jaw jaw, Progress& progress) {
    const bool keepPdl = roles.hasPdl && roles.pdl == PdlLabels::Keep;
    std::vector<std::size_t> bone;
    std::map<int, std::vector<std::size_t>> teeth;
    for (std::size_t s = 0; s < roles.roles.size(); ++s) {
        const LabelRole& r = roles.roles[s];
        if (r.kind == LabelRole::Kind::Bone || (r.kind == LabelRole::Kind::Pdl && !keepPdl)) bone.push_back(s);
        if (r.kind == LabelRole::Kind::Tooth) teeth[r.unn].push_back(s);
    }
    std::vector<std::pair<int, std::vector<std::size_t>>> jobs{{0, bone}};
    jobs.insert(jobs.end(), teeth.begin(), teeth.end());
    std::vector<std::vector<std::size_t>> groups;
    for (const auto& job : jobs) groups.push_back(job.second);
    const std::vector<openvdb::MaskGrid::Ptr> masks = segmentMasks(v, groups);
    std::vector<std::int32_t>().swap(v.values);  // the masks hold what is needed: 2.4 GB of a 0.1 mm jaw
    std::vector<SurfaceMesh> surfaces(jobs.size());
    ProgressStage stage(progress, jawName(jaw) + " label surfaces");
    parallelForFirstErrorInOrder(jobs.size(), progress, [&](std::size_t j) {
        // A kept PDL is the gap between root and socket, 2-4 voxels thick: matching the volume
        // of the solids on both sides would move both its walls into it (4 % of the phantom's
        // PDL, where iso 0 leaves it within 2 % and the solids within 0.5 %).
        surfaces[j] = maskSurface(v, *masks[j], kLabelSmoothingSteps, !keepPdl);
    });
    JawSurfaces out;
    out.jaw = jaw;
    out.pdlKept = keepPdl;
    out.labelVoxelMm = v.directionsMm.colwise().norm().maxCoeff();
    out.bone = std::move(surfaces[0]);
    for (std::size_t j = 1; j < jobs.size(); ++j) out.teeth[jobs[j].first] = std::move(surfaces[j]);
    return out;
}

}  // namespace jawmesh
