// insideOverlapFraction (levelset/InsideOverlap.h) on spheres, where the shared volume is known:
// the lens of two spheres of radius r at distance d has volume pi (4r + d)(2r - d)^2 / 12.
#include "levelset/InsideOverlap.h"

#include <gtest/gtest.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <cmath>

namespace jawmesh {
namespace {

openvdb::FloatGrid::Ptr sphere(double radiusMm, const openvdb::Vec3f& centre, double voxelMm) {
    return openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(static_cast<float>(radiusMm), centre,
                                                                    static_cast<float>(voxelMm), 3.0f);
}

TEST(InsideOverlap, MatchesTheLensVolumeOfTwoSpheres) {
    openvdb::initialize();
    const double r = 2.0, voxel = 0.05, pi = 3.14159265358979323846;
    const auto a = sphere(r, {0, 0, 0}, voxel);
    EXPECT_NEAR(insideOverlapFraction(*a, *a), 1.0, 1e-12);
    EXPECT_EQ(insideOverlapFraction(*a, *sphere(r, {5, 0, 0}, voxel)), 0.0);
    for (double d : {0.5, 1.0, 3.0}) {
        const double lens = pi * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12.0;
        const double expected = lens / (4.0 / 3.0 * pi * r * r * r);
        const double got = insideOverlapFraction(*a, *sphere(r, {static_cast<float>(d), 0, 0}, voxel));
        EXPECT_NEAR(got, expected, 0.02) << "distance " << d;
    }
    // A small sphere inside a large one: all of the smaller one is shared.
    EXPECT_NEAR(insideOverlapFraction(*a, *sphere(0.5, {0.3f, 0, 0}, voxel)), 1.0, 0.01);
}

}  // namespace
}  // namespace jawmesh
