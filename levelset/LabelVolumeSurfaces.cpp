// Implements levelset/LabelVolumeSurfaces.h; what it computes, its rules and its contract are documented there.
#include "levelset/LabelVolumeSurfaces.h"

#include "io/Error.h"
#include "levelset/PhantomSurface.h"

#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/TopologyToLevelSet.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <exception>
#include <map>
#include <set>

namespace jawmesh {
namespace {

/// The voxels of the segments as an index-space mask (voxel (i, j, k) at index (i, j, k)).
openvdb::MaskGrid::Ptr segmentMask(const LabelVolume& v, const std::vector<std::size_t>& segments) {
    std::map<int, std::set<std::int32_t>> valuesByLayer;
    for (std::size_t s : segments) valuesByLayer[v.segments[s].layer].insert(v.segments[s].value);
    auto mask = openvdb::MaskGrid::create();
    auto accessor = mask->getAccessor();
    const std::size_t nx = static_cast<std::size_t>(v.size[0]), nxy = nx * static_cast<std::size_t>(v.size[1]);
    for (const auto& [layer, values] : valuesByLayer) {
        const std::int32_t* data = v.values.data() + static_cast<std::size_t>(layer) * v.voxels();
        const bool one = values.size() == 1;
        const std::int32_t only = *values.begin();
        for (std::size_t i = 0; i < v.voxels(); ++i) {
            const std::int32_t x = data[i];
            if (x == 0 || (one ? x != only : !values.count(x))) continue;
            accessor.setValueOn(openvdb::Coord(static_cast<int>(i % nx), static_cast<int>((i % nxy) / nx), static_cast<int>(i / nxy)));
        }
    }
    return mask;
}

}  // namespace

SurfaceMesh labelSurface(const LabelVolume& v, const std::vector<std::size_t>& segments, int smoothingSteps) {
    const openvdb::MaskGrid::Ptr mask = segmentMask(v, segments);
    if (mask->activeVoxelCount() == 0) throw Error(v.path, "a role has no voxel");
    // Zero set on the voxel faces between the segments and the rest (no closing: it would merge
    // what the segmentation kept apart).
    openvdb::FloatGrid::Ptr levelSet = openvdb::tools::topologyToLevelSet(*mask, 3, 0, 0, 0);
    if (smoothingSteps > 0) {
        openvdb::tools::LevelSetFilter<openvdb::FloatGrid> filter(*levelSet);
        for (int n = 0; n < smoothingSteps; ++n) filter.mean(1);
    }
    SurfaceMesh surface = phantom::extractLevelSetSurface(*levelSet);
    for (Vec3& p : surface.vertices) p = v.worldOf(p.x(), p.y(), p.z());
    // An index-to-world map that mirrors (negative determinant) turns the winding inside out.
    if (signedVolume(surface) < 0)
        for (Tri& t : surface.triangles) std::swap(t[1], t[2]);
    return surface;
}

JawSurfaces surfacesFromLabelVolume(const LabelVolume& v, const LabelAssignment& roles, Jaw jaw, Progress& progress) {
    if (roles.hasPdl && roles.pdl == PdlLabels::Keep)
        throw Error(v.path, "the volume has PDL labels; keeping a segmented PDL is not supported yet: set \"pdl\": "
                            "\"generate\" in labels.json to mesh them as bone and carve the PDL at the requested thickness");
    std::vector<std::size_t> bone;
    std::map<int, std::vector<std::size_t>> teeth;
    for (std::size_t s = 0; s < roles.roles.size(); ++s) {
        const LabelRole& r = roles.roles[s];
        if (r.kind == LabelRole::Kind::Bone || r.kind == LabelRole::Kind::Pdl) bone.push_back(s);
        if (r.kind == LabelRole::Kind::Tooth) teeth[r.unn].push_back(s);
    }
    std::vector<std::pair<int, std::vector<std::size_t>>> jobs{{0, bone}};
    jobs.insert(jobs.end(), teeth.begin(), teeth.end());
    std::vector<SurfaceMesh> surfaces(jobs.size());
    std::vector<std::exception_ptr> errors(jobs.size());
    ProgressStage stage(progress, jawName(jaw) + " label surfaces");
    std::atomic<std::size_t> done{0};
    tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t j) {
        try {
            progress.checkCancelled();
            surfaces[j] = labelSurface(v, jobs[j].second);
        } catch (...) {
            errors[j] = std::current_exception();
        }
        stage.update(static_cast<double>(++done) / static_cast<double>(jobs.size()));
    });
    for (const auto& e : errors)
        if (e) std::rethrow_exception(e);
    JawSurfaces out;
    out.jaw = jaw;
    out.bone = std::move(surfaces[0]);
    for (std::size_t j = 1; j < jobs.size(); ++j) out.teeth[jobs[j].first] = std::move(surfaces[j]);
    return out;
}

}  // namespace jawmesh
