// Interface extraction on synthetic label fields: closed, manifold region boundaries, correct label
// sides, no self-intersections, seeds inside their regions, sub-voxel accuracy, determinism.
#include "filters/ExtractInterfaces.h"
#include "filters/SelfIntersections.h"
#include "filters/TriangleBvh.h"
#include "filters/TriangleGeometry.h"
#include "filters/WellComposedLabels.h"
#include "io/PolyWriter.h"
#include "support/TiledSlabField.h"
#include "support_SyntheticLabels.h"
#include "support_FineExtraction.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <random>
#include <set>

namespace jawmesh {
namespace {

using test::regionLabels;

bool uniformAround(const openvdb::Int32Grid& labels, const openvdb::Coord& v, int reach) {
    const Label L = labels.tree().getValue(v);
    for (int dz = -reach; dz <= reach; ++dz)
        for (int dy = -reach; dy <= reach; ++dy)
            for (int dx = -reach; dx <= reach; ++dx)
                if (labels.tree().getValue(v.offsetBy(dx, dy, dz)) != L) return false;
    return true;
}

// Properties every extraction must have, whatever the field. The enclosure check takes, along
// +-z from sampled triangles, the first voxel with no other label within reachVoxels: 0 for a
// fine surface (the voxels beside it), more where coarse blocks may cut a corner by up to their
// share of the bound.
void expectValidComplex(const InterfaceComplex& c, const LabelField& field, int reachVoxels = 0) {
    ASSERT_EQ(c.sides.size(), c.surface.triangles.size());
    ASSERT_FALSE(c.surface.triangles.empty());
    for (const auto& s : c.sides) ASSERT_LT(s[0], s[1]);
    for (Label L : regionLabels(c)) EXPECT_EQ(test::checkRegionBoundary(c, L), "");
    const auto si = findSelfIntersections(c.surface);
    EXPECT_TRUE(si.pairs.empty()) << si.pairs.size() << " intersecting pairs";
    EXPECT_TRUE(si.degenerate.empty()) << si.degenerate.size() << " degenerate triangles";
    // the boundary of each region encloses exactly that region's voxels (winding number test on
    // voxels next to the interfaces) as extraction prepared them (pockets filled, contacts repaired)
    const auto repaired = labelsToExtract(field);
    for (Label L : regionLabels(c)) {
        const SurfaceMesh b = regionBoundary(c, L);
        std::size_t checked = 0, wrong = 0;
        for (std::size_t t = 0; t < c.surface.triangles.size(); t += 41) {
            const Tri& tri = c.surface.triangles[t];
            const Vec3 centroid = (c.surface.vertices[tri[0]] + c.surface.vertices[tri[1]] +
                                   c.surface.vertices[tri[2]]) / 3.0;
            const auto ijk = repaired->transform().worldToIndexNodeCentered(
                openvdb::Vec3d(centroid.x(), centroid.y(), centroid.z()));
            for (int dz = -1; dz <= 1; dz += 2) {
                openvdb::Coord v = ijk.offsetBy(0, 0, dz);
                for (int step = 1; !uniformAround(*repaired, v, reachVoxels); ++step) {
                    if (step > reachVoxels + 3) break;
                    v = ijk.offsetBy(0, 0, dz * (step + 1));
                }
                if (!uniformAround(*repaired, v, reachVoxels)) continue;
                const auto w = repaired->transform().indexToWorld(v);
                const double wn = test::windingNumber(b, Vec3(w.x(), w.y(), w.z()));
                const bool inside = repaired->tree().getValue(v) == L;
                ++checked;
                if (std::abs(wn - (inside ? 1.0 : 0.0)) > 1e-6) ++wrong;
            }
        }
        EXPECT_GT(checked, 0u) << labelName(L);
        EXPECT_EQ(wrong, 0u) << labelName(L) << ": " << wrong << " of " << checked
                             << " voxel centres on the wrong side";
    }
    // seeds: inside their region (in the well-composed labels), every region has one
    std::set<Label> seeded;
    for (const auto& s : c.seeds) {
        EXPECT_NE(s.label, kOutsideLabel);
        const auto ijk = repaired->transform().worldToIndexNodeCentered(
            openvdb::Vec3d(s.point.x(), s.point.y(), s.point.z()));
        EXPECT_EQ(repaired->tree().getValue(ijk), s.label);
        seeded.insert(s.label);
    }
    EXPECT_EQ(seeded, regionLabels(c));
}

TEST(ExtractInterfaces, JawPhantomIsClosedManifoldAccurate) {
    const double h = 0.05;
    const auto syn = test::jawPhantom(h);
    const InterfaceComplex c = extractInterfaces(syn.field, test::fineExtraction());
    expectValidComplex(c, syn.field);

    // one seed per connected component: every region of the phantom is connected
    std::map<Label, int> seedsPerLabel;
    for (const auto& s : c.seeds) ++seedsPerLabel[s.label];
    for (const auto& [L, n] : seedsPerLabel) EXPECT_EQ(n, 1) << labelName(L);

    // every interface of the phantom is present, the two teeth never touch
    std::set<std::pair<Label, Label>> pairs;
    for (const auto& s : c.sides) pairs.insert({s[0], s[1]});
    EXPECT_TRUE(pairs.count({toothLabel(24), pdlLabel(24)}));
    EXPECT_TRUE(pairs.count({kMandibleBoneLabel, pdlLabel(24)}));
    EXPECT_TRUE(pairs.count({kOutsideLabel, toothLabel(24)}));
    EXPECT_TRUE(pairs.count({kOutsideLabel, kMandibleBoneLabel}));
    EXPECT_FALSE(pairs.count({toothLabel(24), toothLabel(25)}));

    // accuracy: vertices away from junctions lie on the analytic interface of their label pair
    std::vector<std::set<std::pair<Label, Label>>> pairsAt(c.surface.vertices.size());
    for (std::size_t t = 0; t < c.sides.size(); ++t)
        for (auto v : c.surface.triangles[t]) pairsAt[v].insert({c.sides[t][0], c.sides[t][1]});
    // surface nets round the sharp 90-degree edges of the phantom's bone box by up to ~0.7 voxel
    // (real anatomy has none): those vertices get the looser bound
    const auto nearBoxEdge = [&](const Vec3& p) {
        const Vec3 lo(0.0, 0.0, -1.6), hi(3.0, 2.0, 0.0);
        int near = 0;
        for (int k = 0; k < 3; ++k)
            near += std::min(std::abs(p[k] - lo[k]), std::abs(p[k] - hi[k])) < 2.0 * h;
        return near >= 2;
    };
    double worst = 0.0, worstAll = 0.0, sum = 0.0;
    std::size_t n = 0, worstV = 0;
    for (std::size_t v = 0; v < pairsAt.size(); ++v) {
        if (pairsAt[v].size() != 1) continue;
        const auto [a, b] = *pairsAt[v].begin();
        const Vec3& p = c.surface.vertices[v];
        const double e = std::max(std::abs(syn.sdf(a, p)), std::abs(syn.sdf(b, p)));
        worstAll = std::max(worstAll, e);
        sum += e;
        if (nearBoxEdge(p)) continue;
        if (e > worst) worstV = v;
        worst = std::max(worst, e);
        ++n;
    }
    RecordProperty("max_error_voxels", std::to_string(worst / h));
    std::printf("phantom: %zu triangles, %zu vertices, %zu seeds; distance to the analytic interface: "
                "mean %.4f, max %.4f voxel (%.4f at the box edges)\n",
                c.surface.triangles.size(), c.surface.vertices.size(), c.seeds.size(), sum / n / h,
                worst / h, worstAll / h);
    EXPECT_LT(sum / n, 0.1 * h);
    EXPECT_LT(worstAll, 1.0 * h);
    const auto [wa, wb] = *pairsAt[worstV].begin();
    const Vec3& wp = c.surface.vertices[worstV];
    EXPECT_LT(worst, 0.5 * h) << "worst vertex " << wp.transpose() << " on " << labelName(wa) << "|"
                              << labelName(wb) << ": " << syn.sdf(wa, wp) << ", " << syn.sdf(wb, wp);
}

TEST(ExtractInterfaces, AdaptiveIsTheFineSurfaceWithinItsBoundsWithFewerTriangles) {
    const auto syn = test::jawPhantom(0.05);
    ExtractOptions options;
    options.adaptive.boneNearTeethMm = 0.2;  // the phantom's bone is all near its teeth otherwise
    ExtractStats stats;
    const InterfaceComplex adaptive = extractInterfaces(syn.field, options, noProgress(), &stats);
    const InterfaceComplex fine = extractInterfaces(syn.field, test::fineExtraction());
    const InterfaceComplex corners = withoutCarried(adaptive);
    std::printf("phantom: %zu fine triangles, %zu adaptive (%zu blocks, %zu of them far, of %zu cells; carried %.4f, samples %.4f mm)\n",
                fine.surface.triangles.size(), adaptive.surface.triangles.size(), stats.adaptive.blocks, stats.adaptive.farBoneBlocks,
                stats.adaptive.cellsMerged, stats.adaptive.maxCarriedErrorMm, stats.adaptive.maxSampleErrorMm);
    EXPECT_LT(adaptive.surface.triangles.size(), fine.surface.triangles.size() * 3 / 4);
    // the same regions, closed, manifold, of the same topology, intersection-free
    EXPECT_EQ(regionLabels(adaptive), regionLabels(fine));
    for (Label L : regionLabels(fine)) {
        EXPECT_EQ(test::checkRegionBoundary(corners, L), "") << labelName(L);
        EXPECT_EQ(test::eulerAndComponents(regionBoundary(corners, L)), test::eulerAndComponents(regionBoundary(fine, L)))
            << labelName(L);
    }
    EXPECT_TRUE(findSelfIntersections(corners.surface).clean());
    // every fine vertex is a corner or carried, within its share of the bound of its triangle;
    // every fine vertex position is kept (corners and carried vertices are fine vertices)
    ASSERT_EQ(adaptive.surface.vertices.size(), fine.surface.vertices.size());
    std::size_t carried = 0;
    for (std::size_t t = 0; t < adaptive.carried.size(); ++t) {
        const Tri& f = adaptive.surface.triangles[t];
        const auto& V = adaptive.surface.vertices;
        const double bound = options.adaptive.carriedFraction *
                             options.adaptive.bounds.boundMm(adaptive.sides[t][0], adaptive.sides[t][1], false);
        for (std::int32_t p : adaptive.carried[t]) {
            ++carried;
            EXPECT_LE(std::sqrt(squaredDistanceToTriangle(V[std::size_t(p)], V[f[0]], V[f[1]], V[f[2]])), bound + 1e-9);
        }
    }
    EXPECT_EQ(carried + corners.surface.vertices.size(), fine.surface.vertices.size());
    EXPECT_GT(stats.adaptive.blocks, 0u);
    // the other way: sample points of the adaptive triangles near the fine surface of their pair
    const TriangleBvh fineBvh = buildTriangleBvh(fine.surface);
    for (std::size_t t = 0; t < corners.sides.size(); ++t) {
        const Tri& f = corners.surface.triangles[t];
        const Vec3 a = corners.surface.vertices[f[0]], b = corners.surface.vertices[f[1]], c = corners.surface.vertices[f[2]];
        const double bound = options.adaptive.sampleFraction *
                             options.adaptive.bounds.boundMm(corners.sides[t][0], corners.sides[t][1], false);
        for (const Vec3& x : {Vec3((a + b + c) / 3), Vec3((a + b) / 2), Vec3((b + c) / 2), Vec3((c + a) / 2)})
            EXPECT_LE(std::sqrt(closestTriangle(fineBvh, x).squaredDistanceMm2), bound + 1e-9);
    }
}

TEST(ExtractInterfaces, SameOutputWithOneAndTwoThreads) {
    const auto syn = test::jawPhantom(0.06);
    InterfaceComplex one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = extractInterfaces(syn.field);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = extractInterfaces(syn.field);
    }
    ASSERT_EQ(one.surface.vertices.size(), two.surface.vertices.size());
    ASSERT_EQ(one.surface.triangles, two.surface.triangles);
    ASSERT_EQ(one.sides, two.sides);
    for (std::size_t i = 0; i < one.surface.vertices.size(); ++i)
        ASSERT_EQ(one.surface.vertices[i], two.surface.vertices[i]);
    ASSERT_EQ(one.seeds.size(), two.seeds.size());
    for (std::size_t i = 0; i < one.seeds.size(); ++i) ASSERT_EQ(one.seeds[i].point, two.seeds[i].point);
}

TEST(ExtractInterfaces, ThinDiagonalSheetStaysConnected) {
    // tooth | 1-voxel PDL sheet on a diagonal staircase | bone: diagonal-only PDL contacts
    const int n = 16;
    std::vector<Label> lab(std::size_t(n * n * n), kOutsideLabel);
    for (int k = 1; k < n - 1; ++k)
        for (int j = 1; j < n - 1; ++j)
            for (int i = 1; i < n - 1; ++i) {
                const int s = i + j;
                lab[std::size_t(i + n * (j + n * k))] =
                    s < n - 1 ? toothLabel(24) : s == n - 1 ? pdlLabel(24) : kMandibleBoneLabel;
            }
    const LabelField f = test::rawField(lab, n, n, n, 0.05);
    const InterfaceComplex c = extractInterfaces(f);
    expectValidComplex(c, f);
    int pdlSeeds = 0;
    for (const auto& s : c.seeds) pdlSeeds += s.label == pdlLabel(24);
    EXPECT_EQ(pdlSeeds, 1);  // the sheet is one component
    std::set<std::pair<Label, Label>> pairs;
    for (const auto& s : c.sides) pairs.insert({s[0], s[1]});
    EXPECT_FALSE(pairs.count({kMandibleBoneLabel, toothLabel(24)}));  // the sheet is not perforated
}

TEST(ExtractInterfaces, RandomLabelsWithDiagonalContactsAndJunctions) {
    // the nastiest input: every voxel random among four regions (checkerboards, corner contacts,
    // many-region junctions everywhere)
    const Label choices[4] = {kOutsideLabel, kMandibleBoneLabel, toothLabel(24), pdlLabel(24)};
    for (unsigned seed : {1u, 2u, 3u}) {
        std::mt19937 rng(seed);
        const int n = 10;
        std::vector<Label> lab(std::size_t(n * n * n));
        for (auto& L : lab) L = choices[rng() % 4];
        const LabelField f = test::rawField(lab, n, n, n, 0.1);
        const InterfaceComplex c = extractInterfaces(f);
        SCOPED_TRACE("seed " + std::to_string(seed));
        expectValidComplex(c, f);
    }
}

TEST(ExtractInterfaces, EdgeAndCornerContactsOfOneRegion) {
    // two bone cubes touching along an edge, and two touching at a corner
    const int n = 12;
    std::vector<Label> lab(std::size_t(n * n * n), kOutsideLabel);
    auto fill = [&](int x0, int y0, int z0, int x1, int y1, int z1, Label L) {
        for (int k = z0; k < z1; ++k)
            for (int j = y0; j < y1; ++j)
                for (int i = x0; i < x1; ++i) lab[std::size_t(i + n * (j + n * k))] = L;
    };
    fill(1, 1, 1, 4, 4, 5, kMandibleBoneLabel);
    fill(4, 4, 1, 7, 7, 5, kMandibleBoneLabel);  // edge contact
    fill(7, 7, 5, 10, 10, 8, toothLabel(24));
    fill(10, 10, 8, 11, 11, 11, toothLabel(24));  // corner contact
    const LabelField f = test::rawField(lab, n, n, n, 0.05);
    EXPECT_GT(countCriticalCells(*f.labels, f.distances), 0u);
    const InterfaceComplex c = extractInterfaces(f);
    expectValidComplex(c, f);
}

// After a change to a well-composed grid, looking only around the changed voxels repairs it.
TEST(WellComposedLabels, RepairAroundChangedVoxelsOnly) {
    const int n = 16;
    std::vector<Label> lab(std::size_t(n * n * n), kOutsideLabel);
    for (int z = 2; z < 14; ++z)
        for (int y = 2; y < 14; ++y)
            for (int x = 2; x < 8; ++x) lab[std::size_t((z * n + y) * n + x)] = kMandibleBoneLabel;
    const LabelField f = test::rawField(lab, n, n, n, 0.05);
    ASSERT_EQ(countCriticalCells(*f.labels, f.distances), 0u);
    // a bone voxel touching the block along an edge only (bone at (7, 2, 8)): a diagonal contact
    f.labels->tree().setValueOn(openvdb::Coord(8, 1, 8), kMandibleBoneLabel);
    ASSERT_GT(countCriticalCells(*f.labels, f.distances), 0u);
    const std::vector<openvdb::Coord> voxels = {openvdb::Coord(8, 1, 8)};
    EXPECT_GT(makeLabelsWellComposed(*f.labels, f.distances, noProgress(), &voxels), 0u);
    EXPECT_EQ(countCriticalCells(*f.labels, f.distances), 0u);
}

TEST(ExtractInterfaces, LabelChangesBetweenTilesAreClosed) {
    // tiles in the label tree, no distance band over them (see support/TiledSlabField.h)
    const LabelField f = test::tiledSlabField();
    EXPECT_GT(f.labels->tree().activeTileCount(), 0u);
    const ExtractOptions options;
    const InterfaceComplex c = extractInterfaces(f, options);
    // a coarse fan stays within its share of the bound: 0.9 x 0.15 mm far from teeth, 3 voxels
    expectValidComplex(c, f, int(std::ceil(options.adaptive.carriedFraction * options.adaptive.bounds.boneFarErrorMm / f.voxelSizeMm)));
    // the whole slab is enclosed: its boundary reaches the tooth tile's end, 40 voxels along x
    double maxX = 0;
    for (const Vec3& p : c.surface.vertices) maxX = std::max(maxX, p.x());
    EXPECT_NEAR(maxX, 39.5 * f.voxelSizeMm, 0.5 * f.voxelSizeMm);
    std::set<std::pair<Label, Label>> pairs;
    for (const auto& s : c.sides) pairs.insert({s[0], s[1]});
    EXPECT_TRUE(pairs.count({kMandibleBoneLabel, toothLabel(24)}));
}

}  // namespace
}  // namespace jawmesh
