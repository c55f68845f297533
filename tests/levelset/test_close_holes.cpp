// closeSmallHoles() on a generated sphere: a closed surface comes back unchanged; punched holes come
// back closed and consistently oriented, with the enclosed volume of the sphere; long loops stay open.
#include "levelset/CloseHoles.h"
#include "levelset/OrientSurface.h"
#include "support_meshtolevelset.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>

namespace jawmesh {
namespace {
using test::icosphere;

/// Directed edges minus their reverses: all zero on a closed, consistently oriented surface.
std::size_t unmatchedDirectedEdges(const std::vector<Tri>& triangles) {
    std::map<std::pair<std::int32_t, std::int32_t>, int> net;
    for (const Tri& t : triangles)
        for (int k = 0; k < 3; ++k) {
            const std::int32_t a = t[k], b = t[(k + 1) % 3];
            net[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
        }
    std::size_t unmatched = 0;
    for (const auto& [edge, n] : net) unmatched += n != 0;
    return unmatched;
}

TEST(CloseHoles, ClosedSurfaceUnchanged) {
    OrientedSurface s = orientSurface(icosphere(1.0, 3));
    const std::vector<Tri> before = s.triangles;
    const ClosedHoles r = closeSmallHoles(s);
    EXPECT_EQ(r.loops, 0u);
    EXPECT_EQ(r.triangles, 0u);
    EXPECT_EQ(s.triangles, before);
}

TEST(CloseHoles, PunchedSphereClosedWithItsOrientation) {
    OrientedSurface s = orientSurface(test::punchHoles(icosphere(1.0, 4), 6, 0.1, 0.25));
    ASSERT_GT(unmatchedDirectedEdges(s.triangles), 0u);
    const ClosedHoles r = closeSmallHoles(s);
    EXPECT_GT(r.loops, 0u);
    EXPECT_EQ(r.leftOpen, 0u);
    EXPECT_EQ(s.patch.size(), s.triangles.size());
    EXPECT_EQ(unmatchedDirectedEdges(s.triangles), 0u);
    const SurfaceMesh closed{s.vertices, s.triangles};
    // Flat patches over caps of radius <= 0.25 lose a little of the sphere's volume, never its sign.
    EXPECT_NEAR(signedVolume(closed), signedVolume(icosphere(1.0, 4)), 0.02);
}

TEST(CloseHoles, LoopsOverTheLimitStayOpen) {
    OrientedSurface s = orientSurface(test::punchHoles(icosphere(1.0, 4), 3, 0.2, 0.25));
    const std::size_t before = s.triangles.size();
    const ClosedHoles r = closeSmallHoles(s, 3);
    EXPECT_EQ(r.loops, 0u);
    EXPECT_GT(r.leftOpen, 0u);
    EXPECT_EQ(s.triangles.size(), before);
}

}  // namespace
}  // namespace jawmesh
