// tetShape(): the four quality measures on tets whose values are known by hand.
#include "tet/ElementQuality.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace jawmesh;

TEST(ElementQuality, RegularTetScoresOne) {
    const Vec3 a(1, 1, 1), b(-1, 1, -1), c(1, -1, -1), d(-1, -1, 1);
    const TetShape s = tetShape(a, b, c, d);
    ASSERT_GT(s.signedVolume, 0);
    EXPECT_NEAR(s.radiusRatio, 1.0, 1e-12);
    EXPECT_NEAR(s.volumeEdgeRatio, 1.0, 1e-12);
    EXPECT_NEAR(s.radiusEdgeRatio, kRegularRadiusEdgeRatio, 1e-12);
    EXPECT_NEAR(s.minDihedralDeg, std::acos(1.0 / 3.0) * 180 / M_PI, 1e-9);
    EXPECT_NEAR(s.maxDihedralDeg, std::acos(1.0 / 3.0) * 180 / M_PI, 1e-9);
}

TEST(ElementQuality, CornerTetMatchesHandValues) {
    // Corner of the unit cube: V = 1/6, R = sqrt(3)/2, faces 3 x 1/2 + sqrt(3)/2, edges 1,1,1,sqrt2 x3.
    const TetShape s = tetShape(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1));
    const double R = std::sqrt(3.0) / 2, inradius = 0.5 / (1.5 + std::sqrt(3.0) / 2);
    EXPECT_NEAR(s.radiusEdgeRatio, R, 1e-12);
    EXPECT_NEAR(s.radiusRatio, 3 * inradius / R, 1e-12);
    EXPECT_NEAR(s.volumeEdgeRatio, 6 * std::sqrt(2.0) / 6 / std::pow(1.5, 1.5), 1e-12);
    EXPECT_NEAR(s.minDihedralDeg, std::acos(1 / std::sqrt(3.0)) * 180 / M_PI, 1e-9);
    EXPECT_NEAR(s.maxDihedralDeg, 90.0, 1e-9);
}

TEST(ElementQuality, FlatAndNearlyFlatTets) {
    const TetShape flat = tetShape(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0));
    EXPECT_EQ(flat.radiusRatio, 0);
    EXPECT_EQ(flat.volumeEdgeRatio, 0);
    EXPECT_TRUE(std::isinf(flat.radiusEdgeRatio));
    // A sliver: measures go to 0 with its height, the radius-edge ratio stays bounded.
    const TetShape sliver = tetShape(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 1e-3), Vec3(0, 1, 0));
    EXPECT_LT(std::abs(sliver.radiusRatio), 0.01);
    EXPECT_LT(std::abs(sliver.volumeEdgeRatio), 0.01);
    EXPECT_LT(sliver.radiusEdgeRatio, 1.0);
}
