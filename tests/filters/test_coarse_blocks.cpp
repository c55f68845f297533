// blockIsOneDisc and blockIsLayer: which voxel cubes one surface-nets vertex (or one per sheet) may
// stand for (filters/CoarseBlocks.h).
#include "filters/CoarseBlocks.h"
#include "io/Labels.h"

#include <gtest/gtest.h>

#include <functional>

namespace jawmesh {
namespace {

constexpr int kSize = 8;  // the largest block of the adaptive extraction: 8 voxels across
const Label kTooth = toothLabel(24);
const Label kPdl = pdlLabel(24);

/// A label grid with the outside everywhere and `label(x, y, z)` in the closed cube [0, kSize]^3.
openvdb::Int32Grid::Ptr cube(const std::function<Label(int, int, int)>& label) {
    auto grid = openvdb::Int32Grid::create(kOutsideLabel);
    auto acc = grid->getAccessor();
    for (int z = 0; z <= kSize; ++z)
        for (int y = 0; y <= kSize; ++y)
            for (int x = 0; x <= kSize; ++x) acc.setValue({x, y, z}, label(x, y, z));
    return grid;
}

bool anyPair(Label, Label) { return true; }

std::optional<std::array<Label, 2>> test(const openvdb::Int32Grid::Ptr& grid,
                                          const std::function<bool(Label, Label)>& allowed = anyPair) {
    const auto acc = grid->getConstAccessor();
    return blockIsOneDisc(LabelWindow(acc, openvdb::Coord(0, 0, 0), kSize + 1), openvdb::Coord(0, 0, 0), kSize, allowed);
}

TEST(CoarseBlocks, APlaneThroughTheCubeIsOneDisc) {
    const auto slanted = cube([](int x, int y, int z) { return x + y / 2 + z / 3 < 6 ? kTooth : kPdl; });
    const auto disc = test(slanted);
    ASSERT_TRUE(disc.has_value());
    EXPECT_EQ((*disc)[0], std::min(kTooth, kPdl));
    EXPECT_EQ((*disc)[1], std::max(kTooth, kPdl));
    // the caller's rule on label pairs is applied
    EXPECT_FALSE(test(slanted, [](Label, Label) { return false; }).has_value());
}

TEST(CoarseBlocks, ACubeOfOneLabelOrOfThreeIsNot) {
    EXPECT_FALSE(test(cube([](int, int, int) { return kTooth; })).has_value());
    EXPECT_FALSE(test(cube([](int x, int, int) { return x < 3 ? kTooth : x < 6 ? kPdl : kMandibleBoneLabel; })).has_value());
}

TEST(CoarseBlocks, TwoSheetsOrAClosedBubbleAreNotOneDisc) {
    // pdl between two slabs of tooth: the tooth is two components, the interface two discs
    EXPECT_FALSE(test(cube([](int x, int, int) { return x >= 3 && x <= 5 ? kPdl : kTooth; })).has_value());
    // a bubble of pdl inside the tooth: a sphere, and the tooth is a shell (not a ball)
    EXPECT_FALSE(test(cube([](int x, int y, int z) {
                     return x >= 3 && x <= 5 && y >= 3 && y <= 5 && z >= 3 && z <= 5 ? kPdl : kTooth;
                 })).has_value());
    // a plane with a pdl bubble inside the tooth, away from every face and edge: only the ball
    // test sees it (the tooth has a cavity, the pdl two components)
    EXPECT_FALSE(test(cube([](int x, int y, int z) {
                     const bool bubble = x >= 1 && x <= 2 && y >= 3 && y <= 5 && z >= 3 && z <= 5;
                     return x < 4 && !bubble ? kTooth : kPdl;
                 })).has_value());
}

TEST(CoarseBlocks, ATunnelIsNotADisc) {
    // a tooth slab with a square hole through it: a disc with a hole (an annulus)
    const auto annulus = cube([](int x, int y, int z) {
        const bool hole = y >= 3 && y <= 5 && z >= 3 && z <= 5;
        return x < 4 && !hole ? kTooth : kPdl;
    });
    EXPECT_FALSE(test(annulus).has_value());
    // the same slab without the hole is one disc
    EXPECT_TRUE(test(cube([](int x, int, int) { return x < 4 ? kTooth : kPdl; })).has_value());
}

TEST(CoarseBlocks, AFoldThatCrossesAnEdgeTwiceIsNot) {
    // a pdl ridge pushed into the tooth along the whole cube: every edge along y crosses twice
    const auto ridge = cube([](int x, int, int z) { return z < 4 || (x >= 3 && x <= 5) ? kPdl : kTooth; });
    EXPECT_FALSE(test(ridge).has_value());
}

std::optional<BlockLayer> layer(const openvdb::Int32Grid::Ptr& grid, int minGapVoxels = 2) {
    const auto acc = grid->getConstAccessor();
    return blockIsLayer(LabelWindow(acc, openvdb::Coord(0, 0, 0), kSize + 1), openvdb::Coord(0, 0, 0), kSize, minGapVoxels);
}

TEST(CoarseBlocks, APdlLayerBetweenToothAndBoneIsTwoDiscs) {
    // a slanted PDL four voxels thick: two sheets, each one disc, never in one dual cell
    const auto pdl = cube([](int x, int y, int) {
        const int d = x + y / 3;
        return d < 3 ? kTooth : d < 7 ? kPdl : kMandibleBoneLabel;
    });
    const auto found = layer(pdl);
    ASSERT_TRUE(found.has_value());
    EXPECT_EQ(found->middle, kPdl);
    EXPECT_EQ(found->outer[0], std::min(kTooth, kMandibleBoneLabel));
    EXPECT_EQ(found->outer[1], std::max(kTooth, kMandibleBoneLabel));
    EXPECT_FALSE(test(pdl).has_value());  // three labels: no single disc
    // a wider gap than the layer has is refused
    EXPECT_FALSE(layer(pdl, 4).has_value());
}

TEST(CoarseBlocks, AThinOrFoldedLayerIsNot) {
    // one voxel of PDL: tooth and bone share dual cells
    EXPECT_FALSE(layer(cube([](int x, int, int) { return x < 4 ? kTooth : x < 5 ? kPdl : kMandibleBoneLabel; })).has_value());
    // a bone sheet folded back: the bone is two pieces on either side of a tooth slab in the PDL
    EXPECT_FALSE(layer(cube([](int x, int, int) {
                     return x < 2 || x > 7 ? kMandibleBoneLabel : x >= 4 && x <= 5 ? kTooth : kPdl;
                 })).has_value());
    // a layer whose outer sheet has a tunnel (the bone reaches through a hole in the tooth)
    EXPECT_FALSE(layer(cube([](int x, int y, int z) {
                     const bool hole = y >= 3 && y <= 5 && z >= 3 && z <= 5;
                     return x < 2 && !hole ? kTooth : x < 6 ? kPdl : kMandibleBoneLabel;
                 })).has_value());
    // two labels only is not a layer
    EXPECT_FALSE(layer(cube([](int x, int, int) { return x < 4 ? kTooth : kPdl; })).has_value());
}

}  // namespace
}  // namespace jawmesh
