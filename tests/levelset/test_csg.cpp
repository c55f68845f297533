// Boolean and morphological level-set operations on analytic spheres: results must match the
// analytic signed distance within a fraction of a voxel, and inputs must stay untouched.
#include "io/Error.h"
#include "levelset/Csg.h"

#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/Morphology.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

using namespace jawmesh;
using openvdb::Vec3d;

namespace {

constexpr float kSphereVoxelMm = 0.05f;

openvdb::FloatGrid::Ptr sphere(double r, const Vec3d& c) {
    return openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(float(r), openvdb::Vec3f(c), kSphereVoxelMm, 3.0f);
}

/// Largest |grid - analytic| over the active voxels where |analytic| <= within (mm), skipping
/// points where skip() is true.
double maxError(const openvdb::FloatGrid& g, const std::function<double(const Vec3d&)>& exact, double within,
                const std::function<bool(const Vec3d&)>& skip = nullptr) {
    double err = 0;
    std::size_t n = 0;
    for (auto it = g.tree().cbeginValueOn(); it; ++it) {
        const Vec3d p = g.transform().indexToWorld(it.getCoord());
        const double d = exact(p);
        if (std::abs(d) > within || (skip && skip(p))) continue;
        err = std::max(err, std::abs(double(*it) - d));
        ++n;
    }
    EXPECT_GT(n, 100u);
    return err;
}

double sphereSdf(const Vec3d& p, const Vec3d& c, double r) { return (p - c).length() - r; }

}  // namespace

TEST(Csg, UnionIntersectionDifferenceOfSpheres) {
    const Vec3d ca(0, 0, 0), cb(1.2, 0, 0);
    const auto a = sphere(1.0, ca), b = sphere(1.0, cb);
    const auto activeB = b->activeVoxelCount();
    const auto u = csgUnion(*a, *b);
    const auto i = csgIntersection(*a, *b);
    const auto d = csgDifference(*a, *b);
    EXPECT_EQ(b->activeVoxelCount(), activeB) << "an input was modified";
    // Away from the intersection circle (x = 0.6) min / max are true distances.
    auto awayFromCrease = [](const Vec3d& p) { return std::abs(p[0] - 0.6) < 0.5; };
    const double tol = 0.15 * kSphereVoxelMm;
    EXPECT_LT(maxError(*u, [&](const Vec3d& p) { return std::min(sphereSdf(p, ca, 1), sphereSdf(p, cb, 1)); }, 0.1,
                       awayFromCrease), tol);
    EXPECT_LT(maxError(*i, [&](const Vec3d& p) { return std::max(sphereSdf(p, ca, 1), sphereSdf(p, cb, 1)); }, 0.1,
                       [](const Vec3d& p) { return std::abs(p[0] - 0.6) < 0.05; }), tol);
    EXPECT_LT(maxError(*d, [&](const Vec3d& p) { return std::max(sphereSdf(p, ca, 1), -sphereSdf(p, cb, 1)); }, 0.1,
                       awayFromCrease), tol);
    EXPECT_EQ(u->transform(), a->transform());
}

// Accuracy of the rebuilt bands (offset / renormalize): OpenVDB's mesh -> volume alone is within
// 0.03 voxel of the sphere up to 2 voxels from the surface but 0.4-0.5 voxel off at 2-3 voxels
// (measured; a check limited to 2 voxels hides it). Csg.cpp recomputes the band beyond 2 voxels by
// closest-point propagation; measured worst case over the band 0.105-0.125 voxel.
constexpr double kRebuildTolerance = 0.15 * kSphereVoxelMm;

TEST(Csg, OffsetMatchesAnalyticSpheresBeyondTheInputBand) {
    const Vec3d c(0.3, -0.2, 0.1);
    const auto s = sphere(1.5, c);
    for (double dist : {0.05, 0.4, -0.1, -0.5}) {
        const auto o = offsetLevelSet(*s, dist, 3.0);
        SCOPED_TRACE("offset " + std::to_string(dist));
        EXPECT_LT(maxError(*o, [&](const Vec3d& p) { return sphereSdf(p, c, 1.5 + dist); }, 0.15), kRebuildTolerance);
        EXPECT_NEAR(bandHalfWidthMm(*o), 3.0 * kSphereVoxelMm, 1e-6);
    }
}

TEST(Csg, RenormalizeWidensTheBandWithTrueDistances) {
    const Vec3d c(0, 0, 0);
    const auto s = sphere(1.0, c);
    const auto w = renormalizeLevelSet(*s, 10.0, 4.0);
    EXPECT_LT(maxError(*w, [&](const Vec3d& p) { return sphereSdf(p, c, 1.0); }, 0.45), kRebuildTolerance);
    // A distorted field (scaled by 2) comes back as a true distance.
    auto scaled = s->deepCopy();
    for (auto it = scaled->tree().beginValueOn(); it; ++it) it.setValue(*it * 2.0f);
    const auto r = renormalizeLevelSet(*scaled, 3.0, 3.0);
    EXPECT_LT(maxError(*r, [&](const Vec3d& p) { return sphereSdf(p, c, 1.0); }, 0.1), kRebuildTolerance);
}

TEST(Csg, ClosingFillsANarrowGapOpeningRemovesASmallBall) {
    // Two spheres 0.3 mm apart: closing by 0.25 mm fills the gap midway between them.
    const Vec3d ca(0, 0, 0), cb(2.3, 0, 0);
    const auto u = csgUnion(*sphere(1.0, ca), *sphere(1.0, cb));
    const auto closed = closeLevelSet(*u, 0.25);
    auto acc = closed->getConstAccessor();
    auto valueAt = [&](const Vec3d& p) { return acc.getValue(closed->transform().worldToIndexNodeCentered(p)); };
    EXPECT_GT(u->tree().getValue(u->transform().worldToIndexNodeCentered(Vec3d(1.15, 0, 0))), 0.0f);
    EXPECT_LT(valueAt(Vec3d(1.15, 0, 0)), 0.0f);
    // Convex parts far from the gap are unchanged.
    EXPECT_NEAR(valueAt(Vec3d(-1.0, 0, 0)), 0.0, 0.2 * kSphereVoxelMm);
    // A small ball beside a big one: opening by more than its radius removes it, the big one stays.
    const auto both = csgUnion(*sphere(1.0, ca), *sphere(0.2, Vec3d(2.0, 0, 0)));
    const auto opened = openLevelSet(*both, 0.3);
    auto at = [](const openvdb::FloatGrid& g, const Vec3d& p) { return g.tree().getValue(g.transform().worldToIndexNodeCentered(p)); };
    EXPECT_LT(at(*both, Vec3d(2.0, 0, 0)), 0.0f);
    EXPECT_GT(at(*opened, Vec3d(2.0, 0, 0)), 0.0f);
    EXPECT_NEAR(at(*opened, Vec3d(-1.0, 0, 0)), 0.0, 0.2 * kSphereVoxelMm);
}

TEST(Csg, ExtendExteriorDistanceIsEuclideanInsideTheRegionOnly) {
    const Vec3d c(0.1, 0.0, -0.2);
    const auto s = sphere(1.0, c);
    // Region: the band dilated by 10 voxels, cut to the half space x > 0.
    openvdb::MaskTree region(s->tree(), false, openvdb::TopologyCopy());
    openvdb::tools::dilateActiveValues(region, 10, openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::IGNORE_TILES);
    openvdb::MaskTree half(false);
    half.fill(openvdb::CoordBBox(openvdb::Coord(0, -100, -100), openvdb::Coord(100, 100, 100)), true, true);
    half.voxelizeActiveTiles();
    region.topologyIntersection(half);
    const auto x = extendExteriorDistance(*s, region, 0.4);
    EXPECT_NEAR(x->background(), 0.4, 1e-6);
    std::size_t n = 0;
    double err = 0, far = 0;
    for (auto it = x->tree().cbeginValueOn(); it; ++it, ++n) {
        const Vec3d p = x->transform().indexToWorld(it.getCoord());
        EXPECT_GE(p[0], -1e-9) << "outside the region";
        EXPECT_FALSE(s->tree().isValueOn(it.getCoord())) << "band voxels keep their own values";
        err = std::max(err, std::abs(double(*it) - sphereSdf(p, c, 1.0)));
        far = std::max(far, double(*it));
    }
    EXPECT_GT(n, 10000u);
    EXPECT_LT(err, 0.1 * kSphereVoxelMm);
    EXPECT_LE(far, 0.4 + 1e-6);
    EXPECT_GT(far, 0.4 - kSphereVoxelMm);
}

TEST(Csg, RejectsMismatchedTransforms) {
    const auto a = sphere(1.0, Vec3d(0, 0, 0));
    const auto b = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0), 0.07f);
    EXPECT_THROW(csgUnion(*a, *b), Error);
    EXPECT_THROW(offsetLevelSet(*a, std::nan("")), Error);
}
