// The boundary of the union of overlapping shells (levelset/UnionBoundary.h): what the evaluation
// compares a multi-shell tooth with (issue #27).
#include "levelset/UnionBoundary.h"
#include "support/DirtySurfaces.h"
#include "support/Icosphere.h"

#include <gtest/gtest.h>

namespace jawmesh {
namespace {

/// Smallest and largest distance of the mesh's triangle centroids from c.
std::pair<double, double> centroidRadii(const SurfaceMesh& m, const Vec3& c) {
    double lo = 1e9, hi = 0;
    for (const Tri& t : m.triangles) {
        const Vec3 g = (m.vertices[std::size_t(t[0])] + m.vertices[std::size_t(t[1])] + m.vertices[std::size_t(t[2])]) / 3.0;
        lo = std::min(lo, (g - c).norm()), hi = std::max(hi, (g - c).norm());
    }
    return {lo, hi};
}

TEST(UnionBoundary, APulpShellInsideItsToothIsDropped) {
    const SurfaceMesh tooth = test::icosphere(3.0, 3);
    const SurfaceMesh shells = test::withInnerShell(tooth, 0.6);
    ASSERT_EQ(shells.triangles.size(), 2 * tooth.triangles.size());
    const SurfaceMesh boundary = unionBoundary(shells);
    EXPECT_EQ(boundary.triangles.size(), tooth.triangles.size());
    EXPECT_GT(centroidRadii(boundary, Vec3::Zero()).first, 2.9);  // only the outer sphere is left
}

TEST(UnionBoundary, OverlappingShellsKeepOnlyTheirOuterParts) {
    // Two balls of radius 1 whose centres are 1 mm apart: each one's cap inside the other goes.
    SurfaceMesh a = test::icosphere(1.0, 4), b = test::icosphere(1.0, 4, Vec3(1.0, 0, 0));
    SurfaceMesh both = test::unwelded(a);
    const SurfaceMesh bs = test::unwelded(b);
    const auto offset = static_cast<std::int32_t>(both.vertices.size());
    both.vertices.insert(both.vertices.end(), bs.vertices.begin(), bs.vertices.end());
    for (Tri t : bs.triangles) {
        for (auto& v : t) v += offset;
        both.triangles.push_back(t);
    }
    const SurfaceMesh boundary = unionBoundary(both);
    ASSERT_GT(boundary.triangles.size(), 0u);
    EXPECT_LT(boundary.triangles.size(), both.triangles.size());
    for (const Tri& t : boundary.triangles) {
        const Vec3 g = (boundary.vertices[std::size_t(t[0])] + boundary.vertices[std::size_t(t[1])] + boundary.vertices[std::size_t(t[2])]) / 3.0;
        // No kept face lies clearly inside the other ball (faceted radius: 0.99 of 1).
        EXPECT_TRUE(g.norm() > 0.97 || (g - Vec3(1.0, 0, 0)).norm() > 0.97) << g.transpose();
    }
}

TEST(UnionBoundary, OneShellComesBackAsItIs) {
    const SurfaceMesh tooth = test::icosphere(2.0, 2);
    const SurfaceMesh boundary = unionBoundary(test::flipHalf(tooth));
    EXPECT_EQ(boundary.triangles.size(), tooth.triangles.size());
}

}  // namespace
}  // namespace jawmesh
