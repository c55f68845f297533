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
    const std::vector<Coord> cells = dualCellsOf(findLabelEdges(*labels, {}));
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

}  // namespace
}  // namespace jawmesh
