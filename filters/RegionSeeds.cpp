// Implements filters/RegionSeeds.h; what it computes, its rules and its contract are documented there.
#include "filters/RegionSeeds.h"

#include <openvdb/tools/LevelSetUtil.h>

#include <algorithm>
#include <tuple>

namespace jawmesh {
namespace {

struct VoxelCandidate {
    double depth;  // own signed distance, mm (more negative = deeper)
    openvdb::Coord voxel;
    bool operator<(const VoxelCandidate& o) const {
        return depth < o.depth || (depth == o.depth && voxel < o.voxel);
    }
};

bool surroundedBy(const openvdb::Int32Grid::ConstAccessor& acc, const openvdb::Coord& v, Label L) {
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz)
                if (acc.getValue(v.offsetBy(dx, dy, dz)) != L) return false;
    return true;
}

}  // namespace

std::vector<RegionSeed> findRegionSeeds(const openvdb::Int32Grid& labels,
                                        const std::map<Label, openvdb::FloatGrid::Ptr>& distances,
                                        Progress& progress) {
    ProgressStage stage(progress, "region seeds");
    std::map<Label, openvdb::BoolGrid::Ptr> masks;
    for (auto it = labels.tree().cbeginValueAll(); it; ++it) {
        const Label L = *it;
        if (L == kOutsideLabel) continue;
        auto& mask = masks[L];
        if (!mask) mask = openvdb::BoolGrid::create(false);
        if (it.isVoxelValue())
            mask->tree().setValueOn(it.getCoord(), true);
        else
            mask->tree().fill(it.getBoundingBox(), true, true);
    }
    std::vector<RegionSeed> seeds;
    auto acc = labels.getConstAccessor();
    std::size_t done = 0;
    for (const auto& [L, mask] : masks) {
        progress.checkCancelled();
        const auto dit = distances.find(L);
        const openvdb::FloatGrid* dist = dit != distances.end() ? dit->second.get() : nullptr;
        std::vector<openvdb::BoolGrid::Ptr> components;
        openvdb::tools::segmentActiveVoxels(*mask, components);
        for (const auto& comp : components) {
            std::vector<VoxelCandidate> cand;
            for (auto v = comp->tree().cbeginValueOn(); v; ++v) {
                openvdb::Coord c = v.getCoord();
                if (!v.isVoxelValue()) {
                    const auto box = v.getBoundingBox();
                    c = openvdb::Coord((box.min().x() + box.max().x()) / 2,
                                       (box.min().y() + box.max().y()) / 2,
                                       (box.min().z() + box.max().z()) / 2);
                }
                cand.push_back({dist ? double(dist->tree().getValue(c)) : 0.0, c});
            }
            if (cand.empty()) continue;
            std::sort(cand.begin(), cand.end());
            openvdb::Coord best = cand.front().voxel;
            const std::size_t tries = std::min<std::size_t>(cand.size(), 256);
            for (std::size_t i = 0; i < tries; ++i)
                if (surroundedBy(acc, cand[i].voxel, L)) {
                    best = cand[i].voxel;
                    break;
                }
            const auto p = labels.transform().indexToWorld(best);
            seeds.push_back({Vec3(p.x(), p.y(), p.z()), L});
        }
        stage.update(double(++done) / double(masks.size()));
    }
    std::sort(seeds.begin(), seeds.end(), [](const RegionSeed& a, const RegionSeed& b) {
        return std::tie(a.label, a.point.x(), a.point.y(), a.point.z()) <
               std::tie(b.label, b.point.x(), b.point.y(), b.point.z());
    });
    return seeds;
}

}  // namespace jawmesh
