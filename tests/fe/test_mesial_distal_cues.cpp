// The mesial-distal cues of fe/MesialDistalCues.h on shapes whose answer is known: an arch on a
// circle and on a parabola, an elongated and a square crown table, a crown with four cusp bumps.
#include "fe/MesialDistalCues.h"
#include "fe/ToothAxesFromShape.h"
#include "support/SyntheticJaw.h"

#include <gtest/gtest.h>

#include <cmath>

namespace jawmesh {
namespace {
using test::boxSurface;

Vec3 rotatedZ(const Vec3& v, double degrees) {
    const double r = degrees * M_PI / 180.0;
    return {std::cos(r) * v.x() - std::sin(r) * v.y(), std::sin(r) * v.x() + std::cos(r) * v.y(), v.z()};
}

TEST(ArchTangents, FollowACircleAndAParabolaAtEveryTooth) {
    // Crown centres 8 mm apart on a circle of radius 25 mm and 7 mm apart (in x) on the parabola
    // y = x^2 / 40, more curved than a real arch (slope 2.3 at the last tooth). A quadratic in
    // chord length is exact for neither: measured within 0.6 degrees inside the circle and 3.5 at
    // its ends (the fit is extrapolated there), 3.4 on the parabola.
    std::vector<Vec3> circle, parabola;
    for (int i = 0; i < 14; ++i) {
        const double a = (i - 6.5) * 8.0 / 25.0;
        circle.push_back(Vec3(25 * std::sin(a), -25 * std::cos(a), 3.0 + 0.1 * i));
        const double x = (i - 6.5) * 7.0;
        parabola.push_back(Vec3(x, x * x / 40.0, 1.0));
    }
    const std::vector<Vec3> onCircle = archTangents(circle, Vec3::UnitZ());
    const std::vector<Vec3> onParabola = archTangents(parabola, Vec3::UnitZ());
    ASSERT_EQ(onCircle.size(), circle.size());
    for (std::size_t i = 0; i < circle.size(); ++i) {
        const double a = (static_cast<double>(i) - 6.5) * 8.0 / 25.0;
        const bool end = i < 2 || i + 2 >= circle.size();
        EXPECT_LT(angleDeg(onCircle[i], Vec3(std::cos(a), std::sin(a), 0)), end ? 4.0 : 1.0) << "tooth " << i;
        EXPECT_NEAR(onCircle[i].z(), 0.0, 1e-12);
        const double x = parabola[i].x();
        EXPECT_LT(angleDeg(onParabola[i], Vec3(1, x / 20.0, 0)), 4.0) << "tooth " << i;
    }
    EXPECT_TRUE(archTangents({Vec3::Zero()}, Vec3::UnitZ()).empty());
    EXPECT_LT(angleDeg(archTangents({Vec3::Zero(), Vec3(3, 4, 9)}, Vec3::UnitZ())[0], Vec3(0.6, 0.8, 0)), 1e-9);
}

TEST(OcclusalOutline, IsElongatedAlongAnIncisalEdgeAndSquareOnAMolarTable) {
    const SurfaceMesh incisor = boxSurface(Vec3(-4, -1.5, 0), Vec3(4, 1.5, 10), 0.5);
    const CrownOutline edge = occlusalOutline(incisor, Vec3::UnitZ());
    EXPECT_NEAR(std::abs(edge.major.x()), 1.0, 1e-4);  // the split diagonals tilt it slightly
    EXPECT_GT(edge.varianceRatio, 3.0);
    const CrownOutline table = occlusalOutline(boxSurface(Vec3(-5, -5, 0), Vec3(5, 5, 7), 0.5), Vec3::UnitZ());
    EXPECT_NEAR(table.varianceRatio, 1.0, 0.01);
}

/// A square crown table 10 x 10 mm with four round cusps (height 1 mm, radius 2 mm) at (+-2.5,
/// +-2.5), the buccal pair on +y, the whole turned by `turnDeg` about z.
SurfaceMesh molarCrown(double turnDeg) {
    SurfaceMesh crown = boxSurface(Vec3(-5, -5, 0), Vec3(5, 5, 7), 0.25);
    for (Vec3& v : crown.vertices) {
        if (v.z() < 7 - 1e-9) continue;
        for (double cx : {-2.5, 2.5})
            for (double cy : {-2.5, 2.5}) {
                const double r = std::hypot(v.x() - cx, v.y() - cy);
                if (r < 2.0) v.z() += 1.0 - (r / 2.0) * (r / 2.0);
            }
    }
    for (Vec3& v : crown.vertices) v = rotatedZ(v, turnDeg);
    return crown;
}

TEST(CuspTips, AreTheFourCuspsOfAMolarCrown) {
    const SurfaceMesh crown = molarCrown(0);
    const std::vector<Vec3> tips = cuspTips(crown, Vec3::UnitZ());
    ASSERT_EQ(tips.size(), 4u);
    for (const Vec3& t : tips) {
        EXPECT_NEAR(std::abs(t.x()), 2.5, 0.3);
        EXPECT_NEAR(std::abs(t.y()), 2.5, 0.3);
        EXPECT_NEAR(t.z(), 8.0, 0.05);
    }
}

TEST(ChooseMesialDistal, TakesTheToothsOwnDirectionOnlyWhereItIsTrusted) {
    const Vec3 arch = Vec3::UnitX(), labial = Vec3::UnitY();
    // An incisor rotated 20 degrees against the arch follows its incisal edge.
    const SurfaceMesh incisor = boxSurface(Vec3(-4, -1.5, 0), Vec3(4, 1.5, 10), 0.5);
    SurfaceMesh rotated = incisor;
    for (Vec3& v : rotated.vertices) v = rotatedZ(v, 20);
    MesialDistalChoice c = chooseMesialDistal(rotated, Vec3::UnitZ(), arch, labial, false);
    EXPECT_EQ(c.cue, "crown outline");
    EXPECT_NEAR(c.offArchDeg, 20.0, 0.1);
    EXPECT_GT(c.direction.dot(arch), 0);
    // 40 degrees off the arch is not believed: the arch tangent stands.
    for (Vec3& v : rotated.vertices) v = rotatedZ(v, 20);
    c = chooseMesialDistal(rotated, Vec3::UnitZ(), arch, labial, false);
    EXPECT_EQ(c.cue, "arch");
    EXPECT_LT(angleDeg(c.direction, arch), 1e-9);
    // A molar turned 6 degrees follows its buccal cusps; turned 20 it keeps the arch; a square
    // table that is not a molar keeps the arch.
    c = chooseMesialDistal(molarCrown(6), Vec3::UnitZ(), arch, labial, true);
    EXPECT_EQ(c.cue, "buccal cusps");
    EXPECT_NEAR(c.offArchDeg, 6.0, 1.0);
    EXPECT_EQ(chooseMesialDistal(molarCrown(20), Vec3::UnitZ(), arch, labial, true).cue, "arch");
    EXPECT_EQ(chooseMesialDistal(molarCrown(6), Vec3::UnitZ(), arch, labial, false).cue, "arch");
}

}  // namespace
}  // namespace jawmesh
