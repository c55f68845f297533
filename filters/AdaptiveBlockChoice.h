// Internal to the adaptive surface (filters/AdaptiveCells.cpp): which fine dual cells merge into
// which block before any is certified. A block of 2^level cells per side is tried when its labels
// (with a ring) are one disc of one interface or a PDL layer (CoarseBlocks.h), else its children;
// the bone far from the teeth starts one level higher (AdaptiveOptions::farBoneExtraLevels).
#pragma once

#include "filters/CoarseBlocks.h"
#include "filters/DualQuads.h"
#include "io/SurfaceMesh.h"

#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <vector>

namespace jawmesh::adaptive {

using openvdb::Coord;

/// A merged block: dual cells lo .. lo + 2^level - 1 per axis, its member cells and vertex cell.
struct Block {
    Coord lo;
    int level = 0;
    std::vector<std::int32_t> members;
    std::int32_t vertex = -1;
    std::array<Label, 2> sides{};
    // set by the certification (AdaptiveCells.cpp):
    std::vector<std::int32_t> carrier;  ///< per member: the triangle nearest it
    std::vector<std::int32_t> rimQuads; ///< quads with some, not all, cells among the members, sorted
    std::vector<BBox> memberBoxes;      ///< per kMembersPerBox consecutive members: the box of their vertices
    float carriedErrorMm = 0;
    float sampleErrorMm = 0;
};

/// Members per box of Block::memberBoxes.
constexpr std::size_t kMembersPerBox = 16;

/// The block of `level` that holds cell c (a block of level 0).
Coord blockOf(const Coord& c, int level);

/// Where blocks may merge: the ring and the layer gap of AdaptiveOptions.
struct MergeRule {
    int ringVoxels = 1;
    int layerGapVoxels = 0;
};

/// Top-level blocks within `clearanceMm` of a dual cell at a tooth or PDL quad (26-neighbour
/// dilation of those blocks on a grid of blocks).
openvdb::BoolGrid::Ptr blocksNearTeeth(const std::vector<DualQuad>& quads, const std::vector<Coord>& cells,
                                       int level, double blockMm, double clearanceMm);

/// The labels that block lo at `level` and its children are tested on: the block and its ring.
LabelWindow windowOf(const openvdb::Int32Grid::ConstAccessor& labels, const Coord& lo, int level, const MergeRule& rule);

/// Block lo at `level` tried as its eight children: each kept whole (one block per sheet of a
/// layer) when its labels pass the disc or layer test, else tried as its own children.
void chooseInChildren(const LabelWindow& labels, const std::vector<Coord>& cells, const Coord& lo,
                      int level, const MergeRule& rule, const std::vector<std::int32_t>& members, std::vector<Block>& out);

/// Every cell (`cells` sorted, as dualCellsOf gives them) in its block at level `farTop` (top or
/// more), each block tried largest first (parallel, in block order); a block above the top level
/// near the teeth (`near`, on the grid of top-level blocks) starts from its children.
std::vector<Block> initialBlocks(const openvdb::Int32Grid& labels, const std::vector<Coord>& cells, int top,
                                 int farTop, const MergeRule& rule, const openvdb::BoolGrid& near);

}  // namespace jawmesh::adaptive
