// Which vertices count as near a tooth: everything within the distance, nothing far beyond it.
#include "filters/NearTeeth.h"
#include "io/Labels.h"

#include <gtest/gtest.h>

#include <cmath>

namespace jawmesh {
namespace {

/// A small tooth/PDL triangle at the origin and bone/outside triangles with a vertex at x = d_k.
InterfaceComplex lineOfBoneTriangles(const std::vector<double>& xs) {
    InterfaceComplex c;
    auto& V = c.surface.vertices;
    V = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0)};
    c.surface.triangles.push_back({0, 1, 2});
    c.sides.push_back({toothLabel(24), pdlLabel(24)});
    for (double x : xs) {
        const auto i = std::int32_t(V.size());
        V.push_back(Vec3(x, 0, 0));
        V.push_back(Vec3(x + 0.05, 0, 0));
        V.push_back(Vec3(x, 0, 0.05));
        c.surface.triangles.push_back({i, i + 1, i + 2});
        c.sides.push_back({kMandibleBoneLabel, kOutsideLabel});
    }
    return c;
}

TEST(NearTeeth, EverythingWithinTheDistanceIsNearAndFarBeyondIsNot) {
    const double d = 2.0;
    const InterfaceComplex c = lineOfBoneTriangles({0.5, 1.9, 5.0, 9.0, -7.0});
    const std::vector<char> near = verticesNearTeeth(c, d);
    ASSERT_EQ(near.size(), c.surface.vertices.size());
    for (int v = 0; v < 3; ++v) EXPECT_TRUE(near[std::size_t(v)]) << "tooth/PDL vertex " << v;
    // first vertex of each bone triangle
    EXPECT_TRUE(near[3]);   // 0.5 mm away
    EXPECT_TRUE(near[6]);   // 1.9 mm
    const double slack = std::sqrt(3.0) * (d + 2 * d / 4);
    ASSERT_GT(9.0, slack);
    EXPECT_FALSE(near[12]);  // 9 mm
    EXPECT_FALSE(near[15]);  // 7 mm on the other side
    // distance 0: only the tooth's own vertices
    const std::vector<char> own = verticesNearTeeth(c, 0.0);
    for (std::size_t v = 0; v < own.size(); ++v) EXPECT_EQ(bool(own[v]), v < 3) << v;
}

TEST(NearTeeth, NoToothMeansNothingIsNear) {
    InterfaceComplex c = lineOfBoneTriangles({0.0, 1.0});
    c.sides[0] = {kMandibleBoneLabel, kOutsideLabel};
    for (char n : verticesNearTeeth(c, 3.0)) EXPECT_FALSE(n);
}

}  // namespace
}  // namespace jawmesh
