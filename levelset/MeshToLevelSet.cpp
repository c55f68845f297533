// Implements levelset/MeshToLevelSet.h; what it computes, its rules and its contract are documented there.
#include "levelset/MeshToLevelSet.h"

#include "io/Error.h"
#include "io/ResourceUsage.h"
#include "levelset/BandDistance.h"
#include "levelset/CloseHoles.h"
#include "levelset/LineWinding.h"
#include "levelset/OrientSurface.h"
#include "levelset/ScanlineWinding.h"
#include "levelset/UnionBoundary.h"

#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>

namespace jawmesh {

namespace {
using Clock = std::chrono::steady_clock;

// Maps a sub-range of a stage's fraction, so nested steps report into one bar.
class SubProgress : public Progress {
public:
    SubProgress(Progress& p, double from, double to) : p_(p), from_(from), to_(to) {}
    void update(double f) override { p_.update(from_ + (to_ - from_) * f); }
    bool cancelled() const override { return p_.cancelled(); }

private:
    Progress& p_;
    double from_, to_;
};

constexpr int kGridLeafDim = openvdb::FloatTree::LeafNodeType::DIM;  // 8
inline int leafOffset(int x, int y, int z) { return ((x & 7) << 6) | ((y & 7) << 3) | (z & 7); }

// Exact unsigned distance band (levelset/BandDistance.h) as a grid on the shared transform.
openvdb::FloatGrid::Ptr unsignedBand(const std::vector<Vec3>& indexVertices, const std::vector<Tri>& triangles,
                                     const openvdb::math::Transform::Ptr& transform, double voxelSizeMm,
                                     const BandWidths& widths, Progress& progress) {
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(bandDistance(indexVertices, triangles, voxelSizeMm, widths, progress));
    grid->setTransform(transform);
    return grid;
}

// True for triangles with the same sign on both sides (the inner walls of overlapping shells, a
// pulp inside its tooth, stray fins outside): they bound nothing, but the unsigned distance
// would make a spurious near-zero band around them. Candidates are found on the signed grid
// (same sign 1.5 voxels off both faces), which also flags the faces of plates thinner than 3
// voxels, so each candidate is confirmed with Embree lines 0.01 voxel off both faces.
std::vector<char> findNonBoundaryTriangles(const openvdb::FloatGrid& grid, const OrientedSurface& surface,
                                           const std::vector<Vec3>& indexVertices, double voxelSizeMm,
                                           std::size_t& count) {
    const auto& triangles = surface.triangles;
    std::vector<char> internal(triangles.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        auto acc = grid.getConstAccessor();
        for (std::size_t t = r.begin(); t < r.end(); ++t) {
            const Vec3& a = indexVertices[static_cast<std::size_t>(triangles[t][0])];
            const Vec3& b = indexVertices[static_cast<std::size_t>(triangles[t][1])];
            const Vec3& c = indexVertices[static_cast<std::size_t>(triangles[t][2])];
            const Vec3 n = (b - a).cross(c - a).normalized();
            const Vec3 m = (a + b + c) / 3.0;
            auto signAt = [&](const Vec3& p) {
                const openvdb::Coord ijk(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())),
                                         static_cast<int>(std::lround(p.z())));
                return acc.getValue(ijk) < 0.0f;
            };
            internal[t] = signAt(m + 1.5 * n) == signAt(m - 1.5 * n);
        }
    });
    if (std::find(internal.begin(), internal.end(), char(1)) != internal.end()) {
        const LineWindingQuery query(surface.vertices, triangles, {});
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t t = r.begin(); t < r.end(); ++t) {
                if (!internal[t]) continue;
                internal[t] = bothSidesAlike(query, surface.vertices[static_cast<std::size_t>(triangles[t][0])],
                                             surface.vertices[static_cast<std::size_t>(triangles[t][1])],
                                             surface.vertices[static_cast<std::size_t>(triangles[t][2])], 0.01 * voxelSizeMm,
                                             static_cast<int>(t % 64));
            }
        });
    }
    count = static_cast<std::size_t>(std::count(internal.begin(), internal.end(), char(1)));
    return internal;
}

struct Pending {
    std::size_t leaf;
    std::uint16_t offset;
    std::int8_t inside, outside;
};

void requireLevelSetInput(const SurfaceMesh& mesh, double voxelSizeMm, double halfWidthVoxels) {
    if (!(voxelSizeMm > 0.0) || !std::isfinite(voxelSizeMm))
        throw Error("level set: voxel size must be a positive number of mm, got " + std::to_string(voxelSizeMm));
    if (!(halfWidthVoxels >= 1.0) || !std::isfinite(halfWidthVoxels))
        throw Error("level set: band half width must be at least 1 voxel, got " + std::to_string(halfWidthVoxels));
    if (mesh.triangles.empty()) throw Error("level set: the surface has no triangles");
    const BBox box = boundingBox(mesh);
    const double maxIndex = (box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs())).maxCoeff() / voxelSizeMm;
    if (maxIndex > 1.0e8)
        throw Error("level set: the voxel size " + std::to_string(voxelSizeMm) + " mm is too small for a surface spanning " +
                    std::to_string(box.size().maxCoeff()) + " mm");
}

/// Votes of the scanlines through one leaf's active voxels (inside / outside per voxel offset).
/// Lines with an active voxel still open only: after two agreeing votes the third axis cannot
/// change the majority, so it is not asked (a third fewer lookups).
void voteLeaf(const openvdb::FloatTree::LeafNodeType& leaf, const ScanlineWinding& scanlines, std::int8_t inside[512],
              std::int8_t outside[512]) {
    const auto& mask = leaf.getValueMask();
    const openvdb::Coord o = leaf.origin();
    int w[kGridLeafDim];
    for (int axis = 0; axis < 3; ++axis) {
        const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
        for (int du = 0; du < kGridLeafDim; ++du) {
            for (int dv = 0; dv < kGridLeafDim; ++dv) {
                int local[3];
                local[ua] = du;
                local[va] = dv;
                bool any = false;
                for (int a = 0; a < kGridLeafDim && !any; ++a) {
                    local[axis] = a;
                    const int off = leafOffset(local[0], local[1], local[2]);
                    any = mask.isOn(static_cast<openvdb::Index>(off)) && inside[off] < 2 && outside[off] < 2;
                }
                if (!any) continue;
                if (!scanlines.windings(axis, o[ua] + du, o[va] + dv, o[axis], kGridLeafDim, w)) continue;
                for (int a = 0; a < kGridLeafDim; ++a) {
                    local[axis] = a;
                    const int off = leafOffset(local[0], local[1], local[2]);
                    (w[a] >= 1 ? inside : outside)[off] += 1;
                }
            }
        }
    }
}

/// Signs every active voxel by the majority of the reliable scanlines through it; returns the
/// voxels without a majority, in leaf order.
std::vector<Pending> signByScanlines(openvdb::tree::LeafManager<openvdb::FloatTree>& leaves, const ScanlineWinding& scanlines,
                                     Progress& progress) {
    const std::size_t leafCount = leaves.leafCount();
    std::vector<std::vector<Pending>> pendingPerLeaf(leafCount);
    std::atomic<std::size_t> leavesDone{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leafCount, 64), [&](const tbb::blocked_range<std::size_t>& r) {
        progress.checkCancelled();
        for (std::size_t li = r.begin(); li < r.end(); ++li) {
            auto& leaf = leaves.leaf(li);
            std::int8_t inside[512] = {0};
            std::int8_t outside[512] = {0};
            voteLeaf(leaf, scanlines, inside, outside);
            for (auto it = leaf.getValueMask().beginOn(); it; ++it) {
                const openvdb::Index off = it.pos();
                const float d = std::abs(leaf.getValue(off));
                if (inside[off] > outside[off]) leaf.setValueOnly(off, -d);
                else if (outside[off] > inside[off]) leaf.setValueOnly(off, d);
                else pendingPerLeaf[li].push_back({li, static_cast<std::uint16_t>(off), inside[off], outside[off]});
            }
            const std::size_t done = ++leavesDone;
            if (done % 4096 == 0) progress.update(0.75 + 0.15 * static_cast<double>(done) / static_cast<double>(leafCount));
        }
    });
    std::vector<Pending> pending;
    for (auto& v : pendingPerLeaf) pending.insert(pending.end(), v.begin(), v.end());
    return pending;
}

/// Voxels without a scanline majority: more lines, in generic directions, with Embree. Returns
/// how many stay tied (taken as outside).
std::size_t signByLines(std::vector<Pending>& pending, openvdb::tree::LeafManager<openvdb::FloatTree>& leaves,
                        const OrientedSurface& oriented, double voxelSizeMm, Progress& progress) {
    const LineWindingQuery query(oriented.vertices, oriented.triangles, {});
    constexpr int kMaxLines = 16;
    std::atomic<std::size_t> unresolved{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pending.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
        progress.checkCancelled();
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            Pending& p = pending[i];
            auto& leaf = leaves.leaf(p.leaf);
            const openvdb::Coord ijk = leaf.offsetToGlobalCoord(p.offset);
            const Vec3 world = Vec3(ijk.x(), ijk.y(), ijk.z()) * voxelSizeMm;
            // Start the direction sequence at a voxel-dependent place so neighbours differ.
            const int first = static_cast<int>((static_cast<unsigned>(ijk.x()) * 73856093u ^ static_cast<unsigned>(ijk.y()) * 19349663u ^
                                                static_cast<unsigned>(ijk.z()) * 83492791u) % 64u);
            int in = p.inside, out = p.outside;
            for (int k = 0; k < kMaxLines; ++k) {
                if (in + out >= 3 && in != out) break;
                const auto wn = query.windingAlongLine(world, LineWindingQuery::genericDirection(first + k));
                if (wn) (*wn >= 1 ? in : out) += 1;
            }
            if (in == out) ++unresolved;
            const float d = std::abs(leaf.getValue(p.offset));
            leaf.setValueOnly(p.offset, in > out ? -d : d);
        }
    });
    return unresolved.load();
}

/// Triangles inside the union (or outside everything) must not shape the distance: if there are
/// enough of them to matter, the band is recomputed from the boundary triangles alone and takes its
/// signs from `grid` (whose band contains the new one).
openvdb::FloatGrid::Ptr withoutInternalTriangles(openvdb::FloatGrid::Ptr grid, const OrientedSurface& oriented,
                                                 const std::vector<Vec3>& indexVertices, double voxelSizeMm, const BandWidths& widths,
                                                 MeshToLevelSetStats& stats, Progress& progress) {
    const std::vector<char> internal = findNonBoundaryTriangles(*grid, oriented, indexVertices, voxelSizeMm, stats.internalTriangles);
    constexpr std::size_t kMinInternal = 16;
    if (stats.internalTriangles < kMinInternal || stats.internalTriangles >= oriented.triangles.size()) return grid;
    std::vector<Tri> boundary;
    boundary.reserve(oriented.triangles.size() - stats.internalTriangles);
    for (std::size_t t = 0; t < oriented.triangles.size(); ++t)
        if (!internal[t]) boundary.push_back(oriented.triangles[t]);
    SubProgress again(progress, 0.95, 0.99);
    openvdb::FloatGrid::Ptr rebuilt = unsignedBand(indexVertices, boundary, grid->transformPtr(), voxelSizeMm, widths, again);
    openvdb::tree::LeafManager<openvdb::FloatTree> newLeaves(rebuilt->tree());
    newLeaves.foreach([&](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
        auto acc = grid->getConstAccessor();
        for (auto it = leaf.beginValueOn(); it; ++it)
            if (acc.getValue(it.getCoord()) < 0.0f) it.setValue(-std::abs(*it));
    });
    const float background = static_cast<float>(widths.halfWidthVoxels * voxelSizeMm);
    openvdb::tools::signedFloodFillWithValues(rebuilt->tree(), background, -background);
    return rebuilt;
}

}  // namespace

openvdb::FloatGrid::Ptr meshToLevelSet(const SurfaceMesh& mesh, double voxelSizeMm, double halfWidthVoxels,
                                       Progress& progress) {
    MeshToLevelSetStats stats;
    return meshToLevelSet(mesh, voxelSizeMm, halfWidthVoxels, stats, progress);
}

openvdb::FloatGrid::Ptr meshToLevelSet(const SurfaceMesh& mesh, double voxelSizeMm, double halfWidthVoxels,
                                       MeshToLevelSetStats& stats, Progress& progress) {
    return meshToLevelSet(mesh, voxelSizeMm, BandWidths{halfWidthVoxels, halfWidthVoxels, {}}, stats, progress);
}

openvdb::FloatGrid::Ptr meshToLevelSet(const SurfaceMesh& mesh, double voxelSizeMm, const BandWidths& widths,
                                       MeshToLevelSetStats& stats, Progress& progress) {
    requireLevelSetInput(mesh, voxelSizeMm, std::min(widths.halfWidthVoxels, widths.farHalfWidthVoxels));
    stats = MeshToLevelSetStats{};
    stats.inputTriangles = mesh.triangles.size();
    ProgressStage stage(progress, "levelset");

    // 1. Orientation repair, and small holes patched so the distance band runs across them.
    auto t0 = Clock::now();
    OrientedSurface oriented = orientSurface(mesh, progress);
    stats.droppedDegenerate = oriented.droppedDegenerate;
    stats.droppedDuplicate = oriented.droppedDuplicate;
    stats.flippedTriangles = oriented.flipped;
    stats.patches = oriented.patchCount;
    stats.nestedPatches = oriented.nestedPatches;
    stats.secondsOrient = secondsSince(t0);
    if (oriented.triangles.empty()) throw Error("level set: the surface has only degenerate triangles");
    const ClosedHoles holes = closeSmallHoles(oriented);
    stats.holesClosed = holes.loops;
    stats.holePatchTriangles = holes.triangles;
    stats.holesLeftOpen = holes.leftOpen;
    stage.update(0.1);

    // 2. Unsigned narrow band (index-space input).
    t0 = Clock::now();
    const auto transform = openvdb::math::Transform::createLinearTransform(voxelSizeMm);
    std::vector<Vec3> indexVertices(oriented.vertices.size());
    for (std::size_t i = 0; i < indexVertices.size(); ++i) indexVertices[i] = oriented.vertices[i] / voxelSizeMm;
    SubProgress bandProgress(progress, 0.1, 0.6);
    openvdb::FloatGrid::Ptr grid = unsignedBand(indexVertices, oriented.triangles, transform, voxelSizeMm, widths, bandProgress);
    stats.secondsUnsigned = secondsSince(t0);
    stage.update(0.6);

    // 3. Exact scanline crossings along the three axes.
    t0 = Clock::now();
    SubProgress scanProgress(progress, 0.6, 0.75);
    const ScanlineWinding scanlines(indexVertices, oriented.triangles, scanProgress);
    stats.crossings = scanlines.crossingCount();
    stats.secondsScanlines = secondsSince(t0);

    // 4. Sign of every active voxel: majority of the reliable scanlines through it, 5. more lines
    // where there is none, 6. inactive voxels and tiles take the sign of their active neighbours.
    t0 = Clock::now();
    {
        openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid->tree());
        std::vector<Pending> pending = signByScanlines(leaves, scanlines, progress);
        stats.fallbackVoxels = pending.size();
        stage.update(0.9);
        if (!pending.empty()) stats.unresolvedVoxels = signByLines(pending, leaves, oriented, voxelSizeMm, progress);
    }
    const float background = static_cast<float>(widths.halfWidthVoxels * voxelSizeMm);
    openvdb::tools::signedFloodFillWithValues(grid->tree(), background, -background);

    // 7. Without the triangles inside the union, when there are enough to matter.
    grid = withoutInternalTriangles(grid, oriented, indexVertices, voxelSizeMm, widths, stats, progress);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    stats.activeVoxels = static_cast<std::size_t>(grid->activeVoxelCount());
    stats.secondsSign = secondsSince(t0);
    stage.update(1.0);
    return grid;
}

nlohmann::json toJson(const MeshToLevelSetStats& stats) {
    return {{"input_triangles", stats.inputTriangles},
            {"active_voxels", stats.activeVoxels},
            {"repair",
             {{"dropped_degenerate", stats.droppedDegenerate},
              {"dropped_duplicate", stats.droppedDuplicate},
              {"flipped_triangles", stats.flippedTriangles},
              {"patches", stats.patches},
              {"nested_patches", stats.nestedPatches},
              {"holes_closed", stats.holesClosed},
              {"hole_patch_triangles", stats.holePatchTriangles},
              {"holes_left_open", stats.holesLeftOpen}}},
            {"sign",
             {{"crossings", stats.crossings},
              {"internal_triangles", stats.internalTriangles},
              {"fallback_voxels", stats.fallbackVoxels},
              {"unresolved_voxels", stats.unresolvedVoxels}}},
            {"stage_seconds",
             {{"orient", stats.secondsOrient},
              {"unsigned", stats.secondsUnsigned},
              {"scanlines", stats.secondsScanlines},
              {"sign", stats.secondsSign}}}};
}

}  // namespace jawmesh
