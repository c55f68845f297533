// Region wedges around an edge: which region spans which angle, from the triangles' orientation
// and sides alone.
#include "filters/RegionWedges.h"
#include "io/Angles.h"

#include <gtest/gtest.h>

#include <cmath>

namespace jawmesh {
namespace {


/// Apex at `deg` degrees around the z axis edge (0,0,0)-(0,0,1).
Vec3 apexAt(double deg) { return {std::cos(deg * kPi / 180), std::sin(deg * kPi / 180), 0.5}; }

TEST(RegionWedges, JunctionOfThreeRegions) {
    // Tooth (101) between 0 and 12 degrees, PDL (201) from 12 to 200, outside from 200 back to 0.
    // A triangle ordered a -> b has its normal on the side of increasing angle, which is sides[0]
    // when it points there.
    const Vec3 a(0, 0, 0), b(0, 0, 1);
    const EdgeFanTriangle fan[] = {
        {apexAt(0), 0, 101, false},    // ordered b -> a: its normal, into the outside, points back
        {apexAt(12), 201, 101, true},  // PDL on the increasing side
        {apexAt(200), 0, 201, true},   // outside on the increasing side
    };
    EXPECT_NEAR(smallestRegionWedgeDeg(a, b, fan, 3), 12.0, 1e-9);
    // The same fan seen from the other end of the edge gives the same wedges.
    EdgeFanTriangle flipped[3];
    for (int i = 0; i < 3; ++i) flipped[i] = {fan[i].apex, fan[i].front, fan[i].back, !fan[i].aThenB};
    EXPECT_NEAR(smallestRegionWedgeDeg(b, a, flipped, 3), 12.0, 1e-9);
}

TEST(RegionWedges, OutsideAndInconsistentFansDoNotCount) {
    const Vec3 a(0, 0, 0), b(0, 0, 1);
    // A thin sliver of outside (5 degrees) between two bone sheets: not a region wedge.
    const EdgeFanTriangle outsideSliver[] = {{apexAt(0), 0, 1, true}, {apexAt(5), 0, 1, false}};
    EXPECT_NEAR(smallestRegionWedgeDeg(a, b, outsideSliver, 2), 355.0, 1e-9);
    // Labels that do not face each other (a fan seen in part): skipped.
    const EdgeFanTriangle partial[] = {{apexAt(0), 101, 0, true}, {apexAt(5), 201, 1, true}};
    EXPECT_EQ(smallestRegionWedgeDeg(a, b, partial, 2), 360.0);
    EXPECT_EQ(smallestRegionWedgeDeg(a, b, partial, 1), 360.0);
    // The same labels on a whole fan: the surface folds there, no region fits (the punched
    // mandible's failure, issue #27)
    EXPECT_EQ(smallestRegionWedgeDeg(a, b, partial, 2, FanKind::Whole), 0.0);
    // A consistent whole fan is measured as before
    EXPECT_NEAR(smallestRegionWedgeDeg(a, b, outsideSliver, 2, FanKind::Whole), 355.0, 1e-9);
}

TEST(RegionWedges, WholeComplexFindsTheThinEdge) {
    // Two triangles of one tooth's boundary folded to a 8 degree wedge along their shared edge.
    InterfaceComplex c;
    c.surface.vertices = {{0, 0, 0}, {0, 0, 1}, apexAt(0), apexAt(8)};
    // The tooth fills the 8 degrees; both normals point out of it, into the outside (sides[0]).
    c.surface.triangles = {{1, 0, 2}, {0, 1, 3}};
    c.sides = {{0, 101}, {0, 101}};
    const RegionWedgeStats st = measureRegionWedges(c, 10.0);
    EXPECT_NEAR(st.smallestDeg, 8.0, 1e-9);
    EXPECT_EQ(st.edgesBelow, 1u);
    EXPECT_EQ(measureRegionWedges(c, 5.0).edgesBelow, 0u);
}

}  // namespace
}  // namespace jawmesh
