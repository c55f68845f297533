// Computed tooth axes on the phantom, whose axes are known by construction, and the fallback of a
// crown without a labial face. (Real teeth against clinician axes: slow_tooth_axes.cpp.)
#include "fe/ToothAxesFromShape.h"
#include "levelset/Phantom.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

namespace jawmesh {
namespace {

struct Worst {
    double longDeg = 0, labialDeg = 0, centreMm = 0;
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
    }
    return w;
}

// The phantom's construction axis is a whole-tooth axis (crown and root share it), so the
// anatomical axis finds it closely; the clinical crown axis (the default) leans by the taper of
// the phantom's labial faces, which narrow toward the crown top (measured up to 10 degrees).
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
            }
        }
    }
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
