// Computed tooth axes on the phantom, whose axes are known by construction, and the fallback of a
// crown without a labial face. (Real teeth against clinician axes: slow_tooth_axes.cpp.)
#include "fe/ToothAxesFromShape.h"
#include "levelset/Phantom.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <iostream>

namespace jawmesh {
namespace {

struct Worst {
    double longDeg = 0, labialDeg = 0, centreMm = 0;
    double molarLongDeg = 0;  ///< the worst long axis among the molars
};

Worst worstAgainstConstruction(const PhantomJaw& jaw, const AxesFromShapeOptions& options, const SurfaceMesh& bone) {
    const auto computed = toothAxesFromShape(jaw.teeth, jaw.jaw, bone, options);
    EXPECT_EQ(computed.size(), jaw.axes.size());
    Worst w;
    for (const auto& [unn, given] : jaw.axes) {
        const ToothAxes& c = computed.at(unn);
        w.longDeg = std::max(w.longDeg, angleDeg(c.occlusal, given.occlusal));
        w.labialDeg = std::max(w.labialDeg, angleDeg(c.labial, given.labial));
        w.centreMm = std::max(w.centreMm, (c.crownCentre - given.crownCentre).norm());
        if (isMolar(unn)) w.molarLongDeg = std::max(w.molarLongDeg, angleDeg(c.occlusal, given.occlusal));
    }
    return w;
}

// The phantom's construction axis is a whole-tooth axis (crown and root share it), so the
// anatomical axis finds it closely; the clinical crown axis (the default) leans by the taper of
// the phantom's labial faces, which narrow toward the crown top (measured up to 10 degrees).
// Mandibular molars keep the anatomical axis: 0.5-0.9 degrees from the construction axes (their
// buccal face, which leans lingually, would put them 2.4-4.3 off).
TEST(ToothAxesFromShape, RecoversThePhantomAxesInBothJaws) {
    for (Jaw jaw : {Jaw::Mandible, Jaw::Maxilla}) {
        for (std::uint32_t seed : {1u, 2u}) {
            SCOPED_TRACE(jawName(jaw) + " seed " + std::to_string(seed));
            PhantomOptions o;
            o.jaw = jaw;
            o.teeth = 14;
            o.seed = seed;
            o.trianglesScale = 0.3;
            const PhantomJaw phantom = makePhantom(o);
            AxesFromShapeOptions anatomical;
            anatomical.labialFaceRadiusMm = anatomical.molarLabialFaceRadiusMm = 0;
            for (const SurfaceMesh& bone : {SurfaceMesh(), phantom.bone}) {
                const Worst a = worstAgainstConstruction(phantom, anatomical, bone);
                const Worst c = worstAgainstConstruction(phantom, AxesFromShapeOptions(), bone);
                std::cout << jawName(jaw) << " seed " << seed << ": anatomical long " << a.longDeg << ", labial "
                          << a.labialDeg << "; crown axis long " << c.longDeg << ", labial " << c.labialDeg
                          << "; crown centre " << c.centreMm << " mm\n";
                EXPECT_LT(a.longDeg, 7.0);
                EXPECT_LT(a.labialDeg, 7.0);
                EXPECT_LT(c.longDeg, 12.0);
                EXPECT_LT(c.labialDeg, 12.0);
                EXPECT_LT(c.centreMm, 2.5);
                if (jaw == Jaw::Mandible) EXPECT_LT(c.molarLongDeg, 1.5);
            }
        }
    }
}

/// The phantom's arch bent by f(x, y, z) = (1.12 x, 0.92 y + 0.006 x^2, z) (wider, with the back
/// teeth further back) while every tooth stays rigid: each moves to f of its crown centre, turned
/// about the vertical as the arch's tangent turns there, its construction axes with it. The bone is
/// bent by f itself. Teeth of a real wider arch follow it that way; stretching the teeth themselves
/// would turn their crown outlines away from their frames (measured: premolars 9-13 degrees).
PhantomJaw archBent(const PhantomJaw& jaw) {
    auto f = [](const Vec3& p) { return Vec3(1.12 * p.x(), 0.92 * p.y() + 0.006 * p.x() * p.x(), p.z()); };
    PhantomJaw out = jaw;
    for (Vec3& v : out.bone.vertices) v = f(v);
    for (auto& [unn, mesh] : out.teeth) {
        ToothAxes& a = out.axes.at(unn);
        // The arch's tangent at the tooth goes to jacobian * tangent: the tooth turns about the
        // vertical by the angle between the two, so it keeps its place along the arch.
        Eigen::Matrix3d jacobian = Eigen::Matrix3d::Identity();
        jacobian.topLeftCorner<2, 2>() << 1.12, 0.0, 0.012 * a.crownCentre.x(), 0.92;
        const Vec3 tangent = Vec3(a.mesialDistal.x(), a.mesialDistal.y(), 0).normalized();
        const Vec3 bentTangent = (jacobian * tangent).normalized();
        const Eigen::Matrix3d turn =
            Eigen::AngleAxisd(std::atan2(tangent.cross(bentTangent).z(), tangent.dot(bentTangent)), Vec3::UnitZ()).toRotationMatrix();
        const Vec3 centre = a.crownCentre, moved = f(centre);
        for (Vec3& v : mesh.vertices) v = moved + turn * (v - centre);
        a = {moved, turn * a.mesialDistal, turn * a.labial, turn * a.occlusal};
    }
    return out;
}

// Issue #26's phantom variants: the jaw turned 35 degrees about an oblique axis and moved (the
// computed axes must turn with it: nothing may depend on the scanner's frame), and the arch bent
// wider with rigid teeth. Both jaws, whose molars have two (mandible) and three (maxilla)
// divergent roots. Bounds as for the unmoved phantom; the 5 degrees are not met
// (docs/BENCHMARKS.md: the crown axis leans by the taper of the phantom's labial faces).
TEST(ToothAxesFromShape, TurnWithTheJawAndHoldOnABentArch) {
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(35.0 * M_PI / 180.0, Vec3(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
    for (Jaw jaw : {Jaw::Mandible, Jaw::Maxilla}) {
        SCOPED_TRACE(jawName(jaw));
        PhantomOptions o;
        o.jaw = jaw;
        o.trianglesScale = 0.3;
        const PhantomJaw phantom = makePhantom(o);
        const auto plain = toothAxesFromShape(phantom.teeth, jaw, phantom.bone);
        PhantomJaw turned = phantom;
        for (SurfaceMesh* m : {&turned.bone}) for (Vec3& v : m->vertices) v = turn * v + Vec3(40, -25, 110);
        for (auto& [unn, mesh] : turned.teeth) for (Vec3& v : mesh.vertices) v = turn * v + Vec3(40, -25, 110);
        const auto turnedAxes = toothAxesFromShape(turned.teeth, jaw, turned.bone);
        double worstTurn = 0;
        for (const auto& [unn, a] : plain) {
            const ToothAxes& b = turnedAxes.at(unn);
            worstTurn = std::max({worstTurn, angleDeg(turn * a.occlusal, b.occlusal), angleDeg(turn * a.labial, b.labial)});
        }
        std::cout << jawName(jaw) << ": turned jaw's axes within " << worstTurn << " deg of the turned axes\n";
        EXPECT_LT(worstTurn, 0.5);
        const PhantomJaw bent = archBent(phantom);
        const Worst w = worstAgainstConstruction(bent, AxesFromShapeOptions(), bent.bone);
        std::cout << jawName(jaw) << ": bent arch, long " << w.longDeg << ", labial " << w.labialDeg << " deg\n";
        EXPECT_LT(w.longDeg, 12.0);
        EXPECT_LT(w.labialDeg, 12.0);
    }
}

// A tooth whose shape misleads: the mandible's last molar squashed to 35 % of its length along its
// long axis (a short, wide tooth, as a half-erupted or worn molar can be), so its largest spread
// is across it. Its neighbours contradict the axis its shape gives: it takes theirs, and is
// reported; no other tooth is.
TEST(ToothAxesFromShape, ALongAxisItsNeighboursContradictIsReplacedAndReported) {
    PhantomOptions o;
    o.trianglesScale = 0.3;
    PhantomJaw phantom = makePhantom(o);
    const int last = phantom.teeth.rbegin()->first;
    const ToothAxes truth = phantom.axes.at(last);
    for (Vec3& v : phantom.teeth.at(last).vertices) {
        const double h = (v - truth.crownCentre).dot(truth.occlusal);
        v -= 0.65 * h * truth.occlusal;
    }
    std::vector<std::string> notes;
    const auto axes = toothAxesFromShape(phantom.teeth, phantom.jaw, phantom.bone, {}, &notes);
    std::size_t uncertain = 0;
    for (const std::string& n : notes)
        if (n.find("uncertain") != std::string::npos) {
            ++uncertain;
            std::cout << n << "\n";
            EXPECT_EQ(n.rfind("tooth " + std::to_string(last) + ":", 0), 0u) << n;
        }
    EXPECT_EQ(uncertain, 1u);
    const int neighbour = std::prev(phantom.teeth.end(), 2)->first;
    std::cout << "squashed molar " << last << ": long axis " << angleDeg(axes.at(last).occlusal, truth.occlusal)
              << " deg from its construction axis, " << angleDeg(axes.at(last).occlusal, axes.at(neighbour).occlusal)
              << " from its neighbour's; labial " << angleDeg(axes.at(last).labial, truth.labial) << "\n";
    // issue #26's bounds on a real mandible: 10 degrees long, 15 labial (the shape alone: 86 off)
    EXPECT_LT(angleDeg(axes.at(last).occlusal, truth.occlusal), 10.0);
    EXPECT_LT(angleDeg(axes.at(last).labial, truth.labial), 15.0);
    EXPECT_NEAR(axes.at(last).labial.dot(axes.at(last).occlusal), 0.0, 1e-9);
}

/// A bipyramid 18 mm tall and 16.8 mm wide (the long axis is still z): every face is tilted 33
/// degrees from it.
SurfaceMesh bipyramid() {
    SurfaceMesh m;
    m.vertices = {{8.4, 0, 0}, {0, 8.4, 0}, {-8.4, 0, 0}, {0, -8.4, 0}, {0, 0, 9}, {0, 0, -9}};
    for (std::int32_t i = 0; i < 4; ++i) {
        const std::int32_t j = (i + 1) % 4;
        m.triangles.push_back({i, j, 4});
        m.triangles.push_back({j, i, 5});
    }
    return m;
}

TEST(ToothAxesFromShape, KeepsTheAnatomicalAxisWhenTheCrownHasNoLabialFace) {
    std::vector<std::string> notes;
    const auto axes = toothAxesFromShape({{24, bipyramid()}}, Jaw::Mandible, SurfaceMesh(), {}, &notes);
    ASSERT_EQ(axes.size(), 1u);
    EXPECT_NEAR(std::abs(axes.at(24).occlusal.z()), 1.0, 1e-9);
    EXPECT_TRUE(std::any_of(notes.begin(), notes.end(),
                            [](const std::string& n) { return n.find("no labial crown face") != std::string::npos; }));
}

}  // namespace
}  // namespace jawmesh
