// Dual cells of the label edges: the hinted look-up finds every cell (and misses every absent one)
// from any hint, as a plain binary search does.
#include "filters/LabelEdges.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace jawmesh {
namespace {

using openvdb::Coord;

TEST(LabelEdges, HintedCellLookUpAgreesWithBinarySearchFromAnyHint) {
    // a ball of one label in another: its edges' cells are a closed shell, in sorted order
    auto labels = openvdb::Int32Grid::create(kOutsideLabel);
    for (int x = -9; x <= 9; ++x)
        for (int y = -9; y <= 9; ++y)
            for (int z = -9; z <= 9; ++z)
                if (x * x + y * y + z * z <= 64) labels->tree().setValueOn(Coord(x, y, z), kMandibleBoneLabel);
    const std::vector<Coord> cells = dualCellsOf(findLabelEdges(*labels));
    ASSERT_GT(cells.size(), 500u);
    ASSERT_TRUE(std::is_sorted(cells.begin(), cells.end()));

    std::mt19937 rng(7);
    std::uniform_int_distribution<std::size_t> anyIndex(0, cells.size() + 5);
    std::size_t sequential = 0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        EXPECT_EQ(dualCellIndex(cells, cells[i], sequential), std::int64_t(i));  // in order
        std::size_t random = anyIndex(rng);
        EXPECT_EQ(dualCellIndex(cells, cells[i], random), std::int64_t(i));
        EXPECT_EQ(random, i);
        std::size_t last = cells.size() - 1, first = 0;
        EXPECT_EQ(dualCellIndex(cells, cells[i], last), std::int64_t(i));
        EXPECT_EQ(dualCellIndex(cells, cells[i], first), std::int64_t(i));
    }
    // absent cells: inside the ball, outside it, before the first and after the last
    for (const Coord& c : {Coord(0, 0, 0), Coord(30, 0, 0), cells.front().offsetBy(0, 0, -50), cells.back().offsetBy(50, 0, 0)}) {
        ASSERT_FALSE(std::binary_search(cells.begin(), cells.end(), c));
        for (std::size_t hint : {std::size_t(0), cells.size() / 2, cells.size() - 1, cells.size() + 3}) {
            EXPECT_EQ(dualCellIndex(cells, c, hint), -1);
            const std::size_t insertAt = std::size_t(std::lower_bound(cells.begin(), cells.end(), c) - cells.begin());
            EXPECT_EQ(hint, insertAt);
        }
    }
}

TEST(LabelEdges, EveryLabelChangeIsFoundBetweenLeavesTilesAndBackground) {
    // Leaves (a ball), tiles of two labels side by side and against the background (filled boxes,
    // pruned), and a ball straddling a tile's face: every change a brute-force scan finds.
    auto labels = openvdb::Int32Grid::create(kOutsideLabel);
    labels->tree().fill(openvdb::CoordBBox(Coord(0, 0, 0), Coord(31, 15, 15)), kMandibleBoneLabel, true);
    labels->tree().fill(openvdb::CoordBBox(Coord(32, 0, 0), Coord(47, 15, 15)), toothLabel(31), true);
    for (int x = -12; x <= 12; ++x)
        for (int y = -12; y <= 12; ++y)
            for (int z = -12; z <= 12; ++z)
                if (x * x + y * y + z * z <= 100) labels->tree().setValueOn(Coord(x - 20, y, z), pdlLabel(31));
    for (int x = -5; x <= 5; ++x)
        for (int y = -5; y <= 5; ++y)
            for (int z = -5; z <= 5; ++z)
                if (x * x + y * y + z * z <= 20) labels->tree().setValueOn(Coord(x + 32, y + 8, z + 16), pdlLabel(31));
    labels->tree().prune();
    ASSERT_GT(labels->tree().activeTileCount(), 0u);  // tiles as well as leaves

    std::vector<LabelEdge> expected;
    const openvdb::CoordBBox box(Coord(-40, -20, -20), Coord(60, 30, 30));
    auto acc = labels->getConstAccessor();
    for (auto it = box.begin(); it; ++it)
        for (int axis = 0; axis < 3; ++axis) {
            Coord w = *it;
            w[axis] += 1;
            if (acc.getValue(*it) != acc.getValue(w)) expected.push_back({*it, axis});
        }
    const std::vector<LabelEdge> found = findLabelEdges(*labels);
    ASSERT_EQ(found.size(), expected.size());
    for (std::size_t i = 0; i < found.size(); ++i) {
        EXPECT_EQ(found[i].voxel, expected[i].voxel) << i;
        EXPECT_EQ(found[i].axis, expected[i].axis) << i;
    }
}

}  // namespace
}  // namespace jawmesh
