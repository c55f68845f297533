// meshToLevelSet() (and its exact band, bandDistance()) on small generated shapes: distances, signs
// under every kind of corruption the issue lists, determinism across thread counts.
#include "io/Error.h"
#include "levelset/BandDistance.h"
#include "levelset/MeshToLevelSet.h"
#include "levelset/OrientSurface.h"
#include "support_meshtolevelset.h"

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <tbb/global_control.h>

#include <cmath>

namespace jawmesh {
namespace {
using test::checkActiveVoxels;
using test::icosphere;

constexpr double kVoxel = 0.05;

class MeshToLevelSetTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() { openvdb::initialize(); }
};

double sphereSdf(const Vec3& p, const Vec3& c, double r) { return (p - c).norm() - r; }

TEST_F(MeshToLevelSetTest, SphereDistanceAndSignMatchAnalytic) {
    const double r = 1.0;
    MeshToLevelSetStats stats;
    const auto grid = meshToLevelSet(icosphere(r, 4), kVoxel, 3.0, stats);
    ASSERT_TRUE(grid);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_NEAR(grid->voxelSize()[0], kVoxel, 1e-12);
    EXPECT_NEAR(grid->background(), 3.0 * kVoxel, 1e-6);
    EXPECT_EQ(grid->indexToWorld(openvdb::Coord(20, 0, 0)), openvdb::Vec3d(1.0, 0, 0));
    EXPECT_GT(stats.activeVoxels, 10000u);
    // Exact over the whole band (levelset/BandDistance.h): what is left is the faceting of the
    // icosphere (sag about 0.01 voxel); the band holds exactly the voxels nearer than 3 voxels.
    double worst = 0.0;
    std::size_t beyondBand = 0;
    for (auto it = grid->cbeginValueOn(); it; ++it) {
        const openvdb::Vec3d w = grid->indexToWorld(it.getCoord());
        const double exact = sphereSdf(Vec3(w.x(), w.y(), w.z()), Vec3::Zero(), r);
        worst = std::max(worst, std::abs(*it - exact));
        if (std::abs(*it) >= grid->background()) ++beyondBand;
    }
    EXPECT_LT(worst, 0.05 * kVoxel);
    EXPECT_EQ(beyondBand, 0u);
    const auto check = checkActiveVoxels(*grid, [&](const Vec3& p) { return sphereSdf(p, Vec3::Zero(), r); }, 0.1);
    EXPECT_EQ(check.agreed, check.checked);
    // Far inside and far outside (inactive) take the background with the right sign.
    const auto acc = grid->getConstAccessor();
    EXPECT_FLOAT_EQ(acc.getValue(openvdb::Coord(0, 0, 0)), -grid->background());
    EXPECT_FLOAT_EQ(acc.getValue(openvdb::Coord(40, 40, 40)), grid->background());
    EXPECT_EQ(stats.unresolvedVoxels, 0u);
    // The offset-sample checker used on real data agrees too.
    EXPECT_EQ(test::OffsetSampleChecker(icosphere(r, 4), kVoxel).check(*grid).fraction(), 1.0);
}

TEST_F(MeshToLevelSetTest, GridAlignedBoxWithVerticesOnVoxelCentres) {
    // Every vertex and every face lies on voxel centre lines: the degenerate case for ray casts.
    const SurfaceMesh box = test::boxMesh(Vec3(-0.5, -0.3, -0.2), Vec3(0.5, 0.3, 0.2));
    const auto grid = meshToLevelSet(box, kVoxel);
    const auto sdf = [](const Vec3& p) {
        const Vec3 q = p.cwiseAbs() - Vec3(0.5, 0.3, 0.2);
        return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    };
    const auto check = checkActiveVoxels(*grid, sdf, 0.5);
    EXPECT_GT(check.checked, 1000u);
    EXPECT_EQ(check.agreed, check.checked);
}

TEST_F(MeshToLevelSetTest, HolesAFewVoxelsWide) {
    const SurfaceMesh holey = test::punchHoles(icosphere(1.0, 5), 6, 0.08, 0.15);
    ASSERT_LT(holey.triangles.size(), icosphere(1.0, 5).triangles.size());
    MeshToLevelSetStats stats;
    const auto grid = meshToLevelSet(holey, kVoxel, 3.0, stats);
    const auto check = checkActiveVoxels(*grid, [](const Vec3& p) { return sphereSdf(p, Vec3::Zero(), 1.0); });
    EXPECT_GE(check.fraction(), 0.999) << check.agreed << "/" << check.checked;
    EXPECT_GT(stats.holesClosed, 0u);  // patched (levelset/CloseHoles.h), not left to the winding numbers
    EXPECT_EQ(stats.holesLeftOpen, 0u);
    EXPECT_EQ(test::bandlessSignJumps(*grid), 0u);
    EXPECT_FLOAT_EQ(grid->tree().getValue(openvdb::Coord(0, 0, 0)), -grid->background());
}

TEST_F(MeshToLevelSetTest, HalfFlippedAndFullyFlippedSphere) {
    for (const SurfaceMesh& m : {test::flipHalf(icosphere(1.0, 4)), test::flipped(icosphere(1.0, 4))}) {
        MeshToLevelSetStats stats;
        const auto grid = meshToLevelSet(m, kVoxel, 3.0, stats);
        EXPECT_GT(stats.flippedTriangles, 0u);
        const auto check = checkActiveVoxels(*grid, [](const Vec3& p) { return sphereSdf(p, Vec3::Zero(), 1.0); }, 0.1);
        EXPECT_EQ(check.agreed, check.checked);
    }
}

TEST_F(MeshToLevelSetTest, DuplicatedAndZeroAreaFaces) {
    SurfaceMesh m = test::duplicateFaces(icosphere(1.0, 4), 0.3);
    // Zero-area faces: repeated corners and collinear corners.
    const std::size_t n = m.triangles.size();
    for (std::size_t i = 0; i < n; i += 7) {
        const Tri t = m.triangles[i];
        m.triangles.push_back({t[0], t[0], t[1]});
        m.vertices.push_back(0.5 * (m.vertices[static_cast<std::size_t>(t[0])] + m.vertices[static_cast<std::size_t>(t[1])]));
        m.triangles.push_back({t[0], static_cast<std::int32_t>(m.vertices.size() - 1), t[1]});
    }
    MeshToLevelSetStats stats;
    const auto grid = meshToLevelSet(m, kVoxel, 3.0, stats);
    EXPECT_GT(stats.droppedDuplicate, 0u);
    EXPECT_GT(stats.droppedDegenerate, 0u);
    const auto check = checkActiveVoxels(*grid, [](const Vec3& p) { return sphereSdf(p, Vec3::Zero(), 1.0); }, 0.1);
    EXPECT_EQ(check.agreed, check.checked);
}

TEST_F(MeshToLevelSetTest, OverlappingShellsGiveTheirUnion) {
    // Dentin + enamel + pulp thrown together: two overlapping spheres and one inside the first.
    SurfaceMesh m = icosphere(0.8, 4);
    append(m, icosphere(0.6, 4, Vec3(0.9, 0.0, 0.0)));
    append(m, icosphere(0.3, 3, Vec3(-0.2, 0.1, 0.0)));
    const auto grid = meshToLevelSet(m, kVoxel);
    const auto sdf = [](const Vec3& p) { return std::min(sphereSdf(p, Vec3::Zero(), 0.8), sphereSdf(p, Vec3(0.9, 0, 0), 0.6)); };
    const auto check = checkActiveVoxels(*grid, sdf);
    EXPECT_GT(check.checked, 1000u);
    EXPECT_EQ(check.agreed, check.checked);
    // No surface where the shells overlap: on the pulp and on the inner caps the distance is the
    // distance to the union's boundary, not zero.
    const auto acc = grid->getConstAccessor();
    for (const openvdb::Vec3d p : {openvdb::Vec3d(-0.2, 0.1, 0.3), openvdb::Vec3d(0.8, 0.0, 0.0), openvdb::Vec3d(0.3, 0.0, 0.0)}) {
        const Vec3 q(p.x(), p.y(), p.z());
        const float expected = static_cast<float>(std::max(sdf(q), -static_cast<double>(grid->background())));
        EXPECT_NEAR(acc.getValue(grid->transform().worldToIndexCellCentered(p)), expected, 0.5 * kVoxel) << p;
    }
}

TEST_F(MeshToLevelSetTest, InwardShellInsideIsACavity) {
    SurfaceMesh m = icosphere(1.0, 4);
    append(m, test::flipped(icosphere(0.5, 4)));
    MeshToLevelSetStats stats;
    const auto grid = meshToLevelSet(m, kVoxel, 3.0, stats);
    EXPECT_EQ(stats.nestedPatches, 1);
    const auto sdf = [](const Vec3& p) { return std::max(sphereSdf(p, Vec3::Zero(), 1.0), -sphereSdf(p, Vec3::Zero(), 0.5)); };
    const auto check = checkActiveVoxels(*grid, sdf, 0.1);
    EXPECT_EQ(check.agreed, check.checked);
    EXPECT_GT(grid->tree().getValue(openvdb::Coord(0, 0, 0)), 0.0f);  // cavity centre is outside
    EXPECT_LT(grid->tree().getValue(openvdb::Coord(15, 0, 0)), 0.0f);  // the shell wall is inside
}

TEST_F(MeshToLevelSetTest, SmallSelfIntersectionKeepsInsideElsewhere) {
    // Drag one vertex of a sphere across its neighbours so the surface folds over itself.
    SurfaceMesh m = icosphere(1.0, 4);
    std::size_t tip = 0;
    for (std::size_t i = 0; i < m.vertices.size(); ++i)
        if (m.vertices[i].x() > m.vertices[tip].x()) tip = i;
    const Vec3 before = m.vertices[tip];
    m.vertices[tip] = Vec3(0.9, 0.2, 0.05);
    const auto grid = meshToLevelSet(m, kVoxel);
    const auto sdf = [&](const Vec3& p) {
        if ((p - before).norm() < 0.4 || (p - m.vertices[tip]).norm() < 0.4) return 0.0;  // the fold itself
        return sphereSdf(p, Vec3::Zero(), 1.0);
    };
    const auto check = checkActiveVoxels(*grid, sdf);
    EXPECT_GT(check.checked, 1000u);
    EXPECT_EQ(check.agreed, check.checked);
}

// The band against brute force (every voxel of the box around the shape, every triangle): a
// generic sphere, a grid-aligned box (projections that collapse to segments, faces on voxel
// centres), and a soup with a sliver, a zero-area triangle and one triangle spanning many leaves.
TEST_F(MeshToLevelSetTest, BandDistanceIsExactAgainstBruteForce) {
    SurfaceMesh soup;
    soup.vertices = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.5, 1e-7, 0.0},  // sliver
                     {0.0, 0.5, 0.2}, {1.0, 0.5, 0.2}, {0.5, 0.5, 0.2},   // collinear corners
                     {-0.3, -0.2, 0.6}, {1.4, 0.1, 0.9}, {0.2, 1.3, 0.45}};  // large, oblique
    soup.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
    const std::vector<std::pair<const char*, SurfaceMesh>> shapes = {
        {"sphere", icosphere(0.6, 3, Vec3(0.013, -0.021, 0.007))},
        {"box", test::boxMesh(Vec3(-0.5, -0.3, -0.2), Vec3(0.5, 0.3, 0.2))},
        {"soup", soup}};
    const double voxel = 0.1, halfWidth = 3.0;
    for (const auto& [name, mesh] : shapes) {
        SCOPED_TRACE(name);
        std::vector<Vec3> indexVertices;
        for (const Vec3& v : mesh.vertices) indexVertices.push_back(v / voxel);
        const auto tree = bandDistance(indexVertices, mesh.triangles, voxel, halfWidth);
        BBox box;
        for (const Vec3& v : indexVertices) box.extend(v);
        std::size_t checked = 0, wrongMembership = 0;
        double worst = 0.0;
        for (int x = static_cast<int>(std::floor(box.min.x())) - 4; x <= static_cast<int>(std::ceil(box.max.x())) + 4; ++x)
            for (int y = static_cast<int>(std::floor(box.min.y())) - 4; y <= static_cast<int>(std::ceil(box.max.y())) + 4; ++y)
                for (int z = static_cast<int>(std::floor(box.min.z())) - 4; z <= static_cast<int>(std::ceil(box.max.z())) + 4; ++z) {
                    const double exact = test::distanceToTriangles(indexVertices, mesh.triangles, Vec3(x, y, z));
                    float value = 0.0f;
                    const bool active = tree->probeValue(openvdb::Coord(x, y, z), value);
                    ++checked;
                    if (std::abs(exact - halfWidth) < 1e-4) continue;  // membership decided by rounding
                    if (active != (exact < halfWidth)) ++wrongMembership;
                    worst = std::max(worst, std::abs((active ? value / voxel : halfWidth) - std::min(exact, halfWidth)));
                }
        EXPECT_GT(checked, 3000u);
        EXPECT_EQ(wrongMembership, 0u);
        EXPECT_LT(worst, 1e-4);  // voxels
        EXPECT_FLOAT_EQ(tree->background(), static_cast<float>(halfWidth * voxel));
    }
}

TEST_F(MeshToLevelSetTest, TwoWidthBandKeepsTheUniformBandsValues) {
    // Wide (3 voxels) on the x < 0 half of a sphere, 2 voxels elsewhere: every voxel the wide
    // part keeps has the uniform band's value; elsewhere exactly the voxels under 2 voxels do.
    const SurfaceMesh sphere = icosphere(0.6, 3, Vec3(0.013, -0.021, 0.007));
    const double voxel = 0.1;
    std::vector<Vec3> indexVertices;
    for (const Vec3& v : sphere.vertices) indexVertices.push_back(v / voxel);
    const openvdb::CoordBBox wide(openvdb::Coord(-20), openvdb::Coord(-1, 20, 20));
    const auto uniform = bandDistance(indexVertices, sphere.triangles, voxel, 3.0);
    const auto twoWidths = bandDistance(indexVertices, sphere.triangles, voxel, BandWidths{3.0, 2.0, {wide}});
    EXPECT_FLOAT_EQ(twoWidths->background(), uniform->background());
    std::size_t inWide = 0, outside = 0, wrong = 0;
    for (auto it = uniform->cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        float value = 0.0f;
        const bool active = twoWidths->probeValue(c, value);
        const bool kept = wide.isInside(c) || *it < 2.0 * voxel;
        (wide.isInside(c) ? inWide : outside) += 1;
        if (active != kept || (active && value != *it)) ++wrong;
    }
    EXPECT_GT(inWide, 1000u);
    EXPECT_GT(outside, 1000u);
    EXPECT_EQ(wrong, 0u);
    std::size_t extra = 0;  // none the uniform band lacks
    for (auto it = twoWidths->cbeginValueOn(); it; ++it) extra += !uniform->isValueOn(it.getCoord());
    EXPECT_EQ(extra, 0u);
    // The level set keeps its signs: the same as the uniform one's on the voxels both have.
    MeshToLevelSetStats stats;
    const auto a = meshToLevelSet(sphere, voxel, 3.0), b = meshToLevelSet(sphere, voxel, BandWidths{3.0, 2.0, {wide}}, stats);
    std::size_t differ = 0;
    const auto acc = a->getConstAccessor();
    for (auto it = b->cbeginValueOn(); it; ++it) differ += acc.getValue(it.getCoord()) != *it;
    EXPECT_EQ(differ, 0u);
    EXPECT_LT(b->activeVoxelCount(), a->activeVoxelCount());
}

TEST_F(MeshToLevelSetTest, SameGridWithOneAndTwoThreads) {
    // The holey, half-flipped sphere exercises every path (repair, hole patches, scanlines, Embree fallback).
    const SurfaceMesh m = test::flipHalf(test::punchHoles(icosphere(1.0, 5), 6, 0.08, 0.15));
    openvdb::FloatGrid::Ptr a, b;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        a = meshToLevelSet(m, kVoxel);
    }
    {
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        b = meshToLevelSet(m, kVoxel);
    }
    ASSERT_EQ(a->activeVoxelCount(), b->activeVoxelCount());
    std::size_t differ = 0;
    const auto acc = b->getConstAccessor();
    for (auto it = a->cbeginValueOn(); it; ++it)
        if (!acc.isValueOn(it.getCoord()) || acc.getValue(it.getCoord()) != *it) ++differ;
    EXPECT_EQ(differ, 0u);
}

TEST_F(MeshToLevelSetTest, OrientSurfaceTurnsOutermostShellsOutward) {
    const OrientedSurface o = orientSurface(test::flipHalf(icosphere(1.0, 3)));
    SurfaceMesh repaired{o.vertices, o.triangles};
    EXPECT_EQ(o.patchCount, 1);
    EXPECT_NEAR(signedVolume(repaired), signedVolume(icosphere(1.0, 3)), 1e-9);
}

TEST_F(MeshToLevelSetTest, RejectsBadArguments) {
    EXPECT_THROW(meshToLevelSet(icosphere(1.0, 1), 0.0), Error);
    EXPECT_THROW(meshToLevelSet(icosphere(1.0, 1), -1.0), Error);
    EXPECT_THROW(meshToLevelSet(icosphere(1.0, 1), 0.05, 0.5), Error);
    EXPECT_THROW(meshToLevelSet(SurfaceMesh{}, 0.05), Error);
}

}  // namespace
}  // namespace jawmesh
