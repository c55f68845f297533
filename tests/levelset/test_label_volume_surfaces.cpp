// A label's surface (levelset/LabelVolumeSurfaces.h) on a voxelised ball and a voxelised box in an
// oblique, anisotropic grid: closed and outward, every vertex within a voxel of the label
// boundary, the enclosed volume that of the voxels.
#include "io/LabelVolume.h"
#include "io/Error.h"
#include "levelset/LabelVolumeSurfaces.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <map>
#include <utility>

namespace jawmesh {
namespace {

/// 40 x 36 x 30 voxels of 0.2 x 0.25 x 0.3 mm turned 25 degrees: value 1 on the voxels of a ball
/// of radius 3 mm, 2 on a box beside it.
LabelVolume ballAndBox() {
    LabelVolume v;
    v.path = "ball-and-box";
    v.size = {40, 36, 30};
    v.directionsMm = Eigen::AngleAxisd(0.44, Vec3(1, -1, 2).normalized()).toRotationMatrix() * Vec3(0.2, 0.25, 0.3).asDiagonal();
    v.originMm = Vec3(10, -4, 7);
    v.values.assign(v.voxels(), 0);
    const Vec3 centre = v.worldOf(14, 18, 15);
    for (int k = 0; k < v.size[2]; ++k)
        for (int j = 0; j < v.size[1]; ++j)
            for (int i = 0; i < v.size[0]; ++i) {
                std::int32_t& x = v.values[(static_cast<std::size_t>(k) * 36 + j) * 40 + i];
                if ((v.worldOf(i, j, k) - centre).norm() < 3.0) x = 1;
                else if (i >= 30 && i < 37 && j >= 5 && j < 30 && k >= 4 && k < 26) x = 2;
            }
    for (std::int32_t value : {1, 2}) v.segments.push_back({0, value, "", static_cast<std::size_t>(std::count(v.values.begin(), v.values.end(), value))});
    return v;
}

/// True when the 3 x 3 x 3 voxels around the one nearest `world` hold both `value` and another:
/// the label boundary passes within that block, so the point is within a voxel diagonal of it.
bool nearBoundary(const LabelVolume& v, const Vec3& world, std::int32_t value) {
    const Vec3 q = v.directionsMm.inverse() * (world - v.originMm);
    const int c[3] = {static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y())), static_cast<int>(std::lround(q.z()))};
    bool in = false, out = false;
    for (int dk = -1; dk <= 1; ++dk)
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                const int p[3] = {c[0] + di, c[1] + dj, c[2] + dk};
                const bool inside = p[0] >= 0 && p[1] >= 0 && p[2] >= 0 && p[0] < v.size[0] && p[1] < v.size[1] &&
                                    p[2] < v.size[2] &&
                                    v.values[(static_cast<std::size_t>(p[2]) * v.size[1] + p[1]) * v.size[0] + p[0]] == value;
                (inside ? in : out) = true;
            }
    return in && out;
}

TEST(LabelSurface, FollowsTheVoxelsOfAnObliqueAnisotropicGrid) {
    const LabelVolume v = ballAndBox();
    const double voxelMm3 = std::abs(v.directionsMm.determinant());
    for (std::size_t s = 0; s < 2; ++s) {
        SCOPED_TRACE("label " + std::to_string(v.segments[s].value));
        const SurfaceMesh surface = labelSurface(v, {s});
        // Closed: every edge in exactly two triangles, once each way (outward and consistent).
        std::map<std::pair<int, int>, int> edges;
        for (const Tri& t : surface.triangles)
            for (int e = 0; e < 3; ++e) ++edges[{t[static_cast<std::size_t>(e)], t[static_cast<std::size_t>((e + 1) % 3)]}];
        for (const auto& [edge, count] : edges) {
            ASSERT_EQ(count, 1);
            ASSERT_EQ(edges.count({edge.second, edge.first}), 1u);
        }
        const double labelMm3 = static_cast<double>(v.segments[s].voxelCount) * voxelMm3;
        std::cout << "label " << v.segments[s].value << ": surface encloses " << signedVolume(surface) << " mm^3, voxels "
                  << labelMm3 << " mm^3\n";
        // The iso value is set for the voxels' volume (smoothing alone lost 3.5-5 % here).
        EXPECT_NEAR(signedVolume(surface) / labelMm3, 1.0, 0.005);
        std::size_t far = 0;
        for (const Vec3& p : surface.vertices) far += !nearBoundary(v, p, v.segments[s].value);
        EXPECT_EQ(far, 0u) << "vertices farther than a voxel diagonal from the label boundary";
    }
    // The ball's surface is a ball: within a voxel of radius 3 mm about its centre.
    const SurfaceMesh ball = labelSurface(v, {0});
    const Vec3 centre = v.worldOf(14, 18, 15);
    for (const Vec3& p : ball.vertices) EXPECT_NEAR((p - centre).norm(), 3.0, 0.3);
}

TEST(LabelSurface, ARoleWithoutVoxelsIsAnErrorNamingTheVolume) {
    LabelVolume v = ballAndBox();
    v.segments.push_back({0, 7, "", 0});
    EXPECT_THROW(labelSurface(v, {2}), Error);
}

}  // namespace
}  // namespace jawmesh
