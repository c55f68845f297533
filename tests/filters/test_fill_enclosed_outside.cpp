// Enclosed pockets of outside: small ones take the region around them, large cavities and
// channels open to the outside stay.
#include "filters/FillEnclosedOutside.h"

#include <gtest/gtest.h>

namespace jawmesh {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;

void fillBox(openvdb::Int32Grid& g, const CoordBBox& box, Label L) {
    for (auto it = box.begin(); it; ++it) g.tree().setValueOn(*it, L);
}

TEST(FillEnclosedOutside, SmallPocketsFilledCavitiesAndChannelsKept) {
    openvdb::Int32Grid g(kOutsideLabel);
    fillBox(g, CoordBBox(Coord(0), Coord(29)), 1);                        // bone block
    fillBox(g, CoordBBox(Coord(15, 0, 0), Coord(29, 29, 29)), 230);       // PDL half
    fillBox(g, CoordBBox(Coord(5, 5, 5), Coord(6, 6, 6)), kOutsideLabel);  // pocket in bone
    fillBox(g, CoordBBox(Coord(15, 20, 20), Coord(16, 21, 21)), kOutsideLabel);  // pocket at the bone/PDL wall, mostly PDL
    fillBox(g, CoordBBox(Coord(20, 5, 5), Coord(25, 10, 10)), kOutsideLabel);    // cavity of 216 voxels
    fillBox(g, CoordBBox(Coord(0, 20, 3), Coord(8, 20, 3)), kOutsideLabel);      // channel from the surface

    const EnclosedOutsideStats st = fillEnclosedOutside(g, 100);
    EXPECT_EQ(st.pockets, 2u);
    EXPECT_EQ(st.voxels, 16u);
    auto acc = g.getConstAccessor();
    EXPECT_EQ(acc.getValue(Coord(5, 5, 5)), 1);
    EXPECT_EQ(acc.getValue(Coord(6, 6, 6)), 1);
    // the wall pocket touches bone on 4 faces and PDL on 20: it becomes PDL
    EXPECT_EQ(acc.getValue(Coord(15, 20, 20)), 230);
    EXPECT_EQ(acc.getValue(Coord(16, 21, 21)), 230);
    EXPECT_EQ(acc.getValue(Coord(22, 7, 7)), kOutsideLabel);
    EXPECT_EQ(acc.getValue(Coord(4, 20, 3)), kOutsideLabel);
    EXPECT_EQ(acc.getValue(Coord(-1, 0, 0)), kOutsideLabel);
    // a larger limit takes the cavity too; nothing is left to fill afterwards
    EXPECT_EQ(fillEnclosedOutside(g, 1000).pockets, 1u);
    EXPECT_EQ(g.getConstAccessor().getValue(Coord(22, 7, 7)), 230);
    EXPECT_EQ(fillEnclosedOutside(g, 1000).pockets, 0u);
}

}  // namespace
}  // namespace jawmesh
