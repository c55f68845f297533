// Small components: enclosed pockets of outside and cut-off fragments of a region take the label
// around them; large cavities, channels open to the outside and a region's only component stay.
#include "filters/SmallComponents.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace jawmesh {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;

void fillBox(openvdb::Int32Grid& g, const CoordBBox& box, Label L) {
    for (auto it = box.begin(); it; ++it) g.tree().setValueOn(*it, L);
}

TEST(SmallComponents, SmallPocketsFilledCavitiesAndChannelsKept) {
    openvdb::Int32Grid g(kOutsideLabel);
    fillBox(g, CoordBBox(Coord(0), Coord(29)), 1);                        // bone block
    fillBox(g, CoordBBox(Coord(15, 0, 0), Coord(29, 29, 29)), 230);       // PDL half
    fillBox(g, CoordBBox(Coord(5, 5, 5), Coord(6, 6, 6)), kOutsideLabel);  // pocket in bone
    fillBox(g, CoordBBox(Coord(15, 20, 20), Coord(16, 21, 21)), kOutsideLabel);  // pocket at the bone/PDL wall, mostly PDL
    fillBox(g, CoordBBox(Coord(20, 5, 5), Coord(25, 10, 10)), kOutsideLabel);    // cavity of 216 voxels
    fillBox(g, CoordBBox(Coord(0, 20, 3), Coord(8, 20, 3)), kOutsideLabel);      // channel from the surface

    const SmallComponentStats st = absorbSmallComponents(g, 100, 0);
    EXPECT_EQ(st.pockets, 2u);
    EXPECT_EQ(st.pocketVoxels, 16u);
    EXPECT_EQ(st.fragments, 0u);
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
    EXPECT_EQ(absorbSmallComponents(g, 1000, 0).pockets, 1u);
    EXPECT_EQ(g.getConstAccessor().getValue(Coord(22, 7, 7)), 230);
    EXPECT_EQ(absorbSmallComponents(g, 1000, 0).pockets, 0u);
}

TEST(SmallComponents, RegionFragmentsGoToTheirSurroundingsButNoRegionVanishes) {
    openvdb::Int32Grid g(kOutsideLabel);
    fillBox(g, CoordBBox(Coord(0), Coord(29)), 1);                             // bone
    fillBox(g, CoordBBox(Coord(10, 10, 10), Coord(19, 19, 19)), 230);          // PDL block in bone
    fillBox(g, CoordBBox(Coord(12, 12, 12), Coord(17, 17, 17)), 130);          // tooth in the PDL
    g.tree().setValueOn(Coord(3, 3, 3), 230);                                  // PDL speck in bone
    fillBox(g, CoordBBox(Coord(11, 11, 11), Coord(11, 12, 11)), 1);            // bone speck in the PDL
    fillBox(g, CoordBBox(Coord(29, 0, 0), Coord(30, 1, 0)), 230);              // PDL speck at the bone surface, 2 of 4 voxels in air
    g.tree().setValueOn(Coord(25, 25, 25), 131);                               // a region of one voxel only
    fillBox(g, CoordBBox(Coord(15, 15, 15), Coord(15, 15, 15)), 130);          // (inside the tooth: no change)

    std::vector<Coord> relabelled;
    const SmallComponentStats st = absorbSmallComponents(g, 0, 8, &relabelled);
    EXPECT_EQ(st.fragments, 3u);
    std::sort(relabelled.begin(), relabelled.end());
    const std::vector<Coord> expected = {Coord(3, 3, 3),  Coord(11, 11, 11), Coord(11, 12, 11), Coord(29, 0, 0),
                                         Coord(29, 1, 0), Coord(30, 0, 0),   Coord(30, 1, 0)};
    EXPECT_EQ(relabelled, expected);
    EXPECT_EQ(st.fragmentVoxels, 1u + 2u + 4u);
    EXPECT_EQ(st.pockets, 0u);
    auto acc = g.getConstAccessor();
    EXPECT_EQ(acc.getValue(Coord(3, 3, 3)), 1);
    EXPECT_EQ(acc.getValue(Coord(11, 11, 11)), 230);
    EXPECT_EQ(acc.getValue(Coord(11, 12, 11)), 230);
    // the surface speck has more faces on air (outside) than on bone
    EXPECT_EQ(acc.getValue(Coord(30, 0, 0)), kOutsideLabel);
    EXPECT_EQ(acc.getValue(Coord(29, 1, 0)), kOutsideLabel);
    // the region's only component stays, however small; the big ones are untouched
    EXPECT_EQ(acc.getValue(Coord(25, 25, 25)), 131);
    EXPECT_EQ(acc.getValue(Coord(14, 14, 14)), 130);
    EXPECT_EQ(acc.getValue(Coord(10, 19, 10)), 230);
    // idempotent
    EXPECT_EQ(absorbSmallComponents(g, 0, 8).fragments, 0u);
}

// Hundreds of thousands of start voxels (the search runs in chunks of them): every pocket is found
// once, whichever chunks its starts fall in, and the label edges updated around what was relabelled
// are the edges found again from scratch.
TEST(SmallComponents, ManyPocketsEachFoundOnceAndTheEdgesUpdated) {
    openvdb::Int32Grid g(kOutsideLabel);
    fillBox(g, CoordBBox(Coord(0), Coord(89)), 1);
    int made = 0;
    for (int x = 2; x < 87; x += 3)  // 2-voxel pockets in every slab pair: chunk borders cut through some
        for (int y = 2; y < 87; y += 6)
            for (int z = 2; z < 87; z += 6) {
                fillBox(g, CoordBBox(Coord(x, y, z), Coord(x + 1, y, z)), kOutsideLabel);
                ++made;
            }
    std::vector<LabelEdge> edges = findLabelEdges(g);
    ASSERT_GT(2 * edges.size(), std::size_t(1) << 17);  // more than one chunk of starts
    std::vector<Coord> relabelled;
    const SmallComponentStats st = absorbSmallComponents(g, 8, 0, &relabelled, &edges);
    EXPECT_EQ(st.pockets, std::size_t(made));
    EXPECT_EQ(st.pocketVoxels, 2 * std::size_t(made));
    EXPECT_EQ(relabelled.size(), 2 * std::size_t(made));
    updateLabelEdges(edges, g, relabelled);
    const std::vector<LabelEdge> again = findLabelEdges(g);
    ASSERT_EQ(edges.size(), again.size());
    for (std::size_t i = 0; i < edges.size(); ++i) {
        EXPECT_EQ(edges[i].voxel, again[i].voxel);
        EXPECT_EQ(edges[i].axis, again[i].axis);
    }
}

}  // namespace
}  // namespace jawmesh
