// Implements filters/AdaptiveBlockChoice.h; what it computes, its rules and its contract are documented there.
#include "filters/AdaptiveBlockChoice.h"

#include <openvdb/tools/Morphology.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace jawmesh::adaptive {
namespace {

int floorShift(int x, int level) { return x >= 0 ? x >> level : -((-x + (1 << level) - 1) >> level); }
Coord scaled(const Coord& c, int s) { return Coord(c.x() * s, c.y() * s, c.z() * s); }

/// A sheet that a block's cells may merge into one vertex: its label pair and, for a sheet of a
/// layer, the outer label that its cells hold (the other sheet's cells do not).
struct Sheet {
    std::array<Label, 2> sides;
    std::optional<Label> outer;
};

/// The sheets of block lo at `level`: its one pair when the block and the cube ringVoxels larger
/// around it are one disc of it (no other sheet, no third label nearby); else, when that cube is a
/// layer (CoarseBlocks.h), the layer's sheets that the block holds, each one disc in the block.
std::vector<Sheet> blockSheets(const LabelWindow& labels, const Coord& lo, int level,
                               int ringVoxels, int layerGapVoxels) {
    const int size = 1 << level;
    const Coord voxelLo(lo.x() * size, lo.y() * size, lo.z() * size);
    const auto any = [](Label, Label) { return true; };
    const auto pair = blockIsOneDisc(labels, voxelLo, size, any);
    const int ring = std::max(ringVoxels, 0);
    if (pair && ring == 0) return {{*pair, std::nullopt}};
    if (pair) {
        const auto around = blockIsOneDisc(labels, voxelLo.offsetBy(-ring), size + 2 * ring, any);
        if (around && *around == *pair) return {{*pair, std::nullopt}};
    }
    if (layerGapVoxels <= 0) return {};
    const auto layer = blockIsLayer(labels, voxelLo.offsetBy(-ring), size + 2 * ring, layerGapVoxels);
    // the PDL only: its thickness is the carve's own; any other layer (a bone lip between the PDL
    // and the outside) may be a plate barely over the gap, whose tets two coarse sheets flatten
    if (!layer || layer->middle == kOutsideLabel || labelKind(layer->middle) != LabelKind::Pdl) return {};
    const auto sheetOf = [&](Label outer) {
        return Sheet{{std::min(outer, layer->middle), std::max(outer, layer->middle)}, outer};
    };
    if (pair) {  // one sheet of the layer crosses the block
        for (Label outer : layer->outer)
            if (*pair == sheetOf(outer).sides) return {sheetOf(outer)};
        return {};
    }
    const auto inner = ring == 0 ? layer : blockIsLayer(labels, voxelLo, size, layerGapVoxels);
    if (!inner || inner->middle != layer->middle || inner->outer != layer->outer) return {};
    return {sheetOf(layer->outer[0]), sheetOf(layer->outer[1])};
}

/// Whether dual cell c holds a voxel of label l.
bool cellHolds(const LabelWindow& labels, const Coord& c, Label l) {
    for (int k = 0; k < 8; ++k)
        if (labels.at(dualCellCorner(c, k)) == l) return true;
    return false;
}

/// Child k (0..7, x in bit 0, y in bit 1, z in bit 2) of block lo, one level down.
Coord childBlock(const Coord& lo, int k) { return Coord(2 * lo.x() + (k & 1), 2 * lo.y() + ((k >> 1) & 1), 2 * lo.z() + ((k >> 2) & 1)); }

/// The members of block lo at `level` by the child (childBlock) that holds them, in their order.
std::array<std::vector<std::int32_t>, 8> membersByChild(const std::vector<Coord>& cells, const Coord& lo, int level,
                                                        const std::vector<std::int32_t>& members) {
    std::array<std::vector<std::int32_t>, 8> child;
    const int half = 1 << (level - 1);
    for (std::int32_t m : members) {
        const Coord c = cells[std::size_t(m)] - scaled(lo, 1 << level);
        child[std::size_t((c.x() >= half) | ((c.y() >= half) << 1) | ((c.z() >= half) << 2))].push_back(m);
    }
    return child;
}

void chooseBlocks(const LabelWindow& labels, const std::vector<Coord>& cells, const Coord& lo,
                  int level, const MergeRule& rule, std::vector<std::int32_t> members, std::vector<Block>& out);


}  // namespace

Coord blockOf(const Coord& c, int level) { return Coord(floorShift(c.x(), level), floorShift(c.y(), level), floorShift(c.z(), level)); }

openvdb::BoolGrid::Ptr blocksNearTeeth(const std::vector<DualQuad>& quads, const std::vector<Coord>& cells,
                                       int level, double blockMm, double clearanceMm) {
    auto near = openvdb::BoolGrid::create(false);
    auto acc = near->getAccessor();
    for (const DualQuad& q : quads) {
        const auto toothOrPdl = [](Label l) {
            return l != kOutsideLabel && (isToothLike(labelKind(l)) || labelKind(l) == LabelKind::Pdl);
        };
        if (!toothOrPdl(q.sides[0]) && !toothOrPdl(q.sides[1])) continue;
        for (std::int32_t c : q.cells) acc.setValueOn(blockOf(cells[std::size_t(c)], level), true);
    }
    const int steps = int(std::ceil(clearanceMm / blockMm)) + 1;
    if (steps > 0) openvdb::tools::dilateActiveValues(near->tree(), steps, openvdb::tools::NN_FACE_EDGE_VERTEX);
    return near;
}

LabelWindow windowOf(const openvdb::Int32Grid::ConstAccessor& labels, const Coord& lo, int level, const MergeRule& rule) {
    const int size = 1 << level, ring = std::max(rule.ringVoxels, 0);
    return LabelWindow(labels, scaled(lo, size).offsetBy(-ring), size + 1 + 2 * ring);
}

void chooseInChildren(const LabelWindow& labels, const std::vector<Coord>& cells, const Coord& lo,
                      int level, const MergeRule& rule, const std::vector<std::int32_t>& members, std::vector<Block>& out) {
    auto child = membersByChild(cells, lo, level, members);
    for (int k = 0; k < 8; ++k) chooseBlocks(labels, cells, childBlock(lo, k), level - 1, rule, std::move(child[std::size_t(k)]), out);
}

namespace {

/// The blocks among `members` (cells of block lo at `level`) that pass the disc or layer test,
/// largest first: a block that fails is tried as its eight children. A layer gives a block per
/// sheet, each with the members that hold its outer label.
void chooseBlocks(const LabelWindow& labels, const std::vector<Coord>& cells, const Coord& lo,
                  int level, const MergeRule& rule, std::vector<std::int32_t> members, std::vector<Block>& out) {
    if (level <= 0 || members.empty()) return;
    const std::vector<Sheet> sheets = blockSheets(labels, lo, level, rule.ringVoxels, rule.layerGapVoxels);
    if (sheets.empty()) return chooseInChildren(labels, cells, lo, level, rule, members, out);
    for (const Sheet& sheet : sheets) {
        Block b;
        b.lo = lo;
        b.level = level;
        b.sides = sheet.sides;
        for (std::int32_t m : members)
            if (!sheet.outer || cellHolds(labels, cells[std::size_t(m)], *sheet.outer)) b.members.push_back(m);
        if (!b.members.empty()) out.push_back(std::move(b));
    }
}


/// Block lo at `level` (at least `top`) as chooseBlocks, but one above the top level with a
/// descendant of the top level near the teeth (`near`) is tried as its eight children.
void chooseAwayFromTeeth(const LabelWindow& labels, const std::vector<Coord>& cells, const Coord& lo, int level, int top,
                         const MergeRule& rule, const openvdb::BoolGrid& near, std::vector<std::int32_t> members,
                         std::vector<Block>& out) {
    if (level <= top || members.empty()) return chooseBlocks(labels, cells, lo, level, rule, std::move(members), out);
    const int n = 1 << (level - top);
    const Coord first = scaled(lo, n);
    bool nearTeeth = false;
    const auto nearAcc = near.getConstAccessor();
    for (int x = 0; x < n && !nearTeeth; ++x)
        for (int y = 0; y < n && !nearTeeth; ++y)
            for (int z = 0; z < n && !nearTeeth; ++z) nearTeeth = nearAcc.isValueOn(first.offsetBy(x, y, z));
    if (!nearTeeth) return chooseBlocks(labels, cells, lo, level, rule, std::move(members), out);
    auto child = membersByChild(cells, lo, level, members);
    for (int k = 0; k < 8; ++k)
        chooseAwayFromTeeth(labels, cells, childBlock(lo, k), level - 1, top, rule, near, std::move(child[std::size_t(k)]), out);
}

/// (block at `level`, cell) for every cell, sorted: by block, then cell. The cells are sorted (x
/// first), so each x-slab of blocks holds a run of them, sorted on its own (one sort of all 13 M
/// pairs of the mandible was most of a second).
std::vector<std::pair<Coord, std::int32_t>> cellsByBlock(const std::vector<Coord>& cells, int level) {
    std::vector<std::pair<Coord, std::int32_t>> byBlock(cells.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 1 << 14), [&](const auto& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) byBlock[c] = {blockOf(cells[c], level), std::int32_t(c)};
    });
    std::vector<std::size_t> slabStart;
    for (std::size_t i = 0; i < byBlock.size(); ++i)
        if (i == 0 || byBlock[i].first.x() != byBlock[i - 1].first.x()) slabStart.push_back(i);
    slabStart.push_back(byBlock.size());
    tbb::parallel_for(std::size_t(0), slabStart.size() - 1, [&](std::size_t s) {
        std::sort(byBlock.begin() + std::ptrdiff_t(slabStart[s]), byBlock.begin() + std::ptrdiff_t(slabStart[s + 1]));
    });
    return byBlock;
}

}  // namespace

std::vector<Block> initialBlocks(const openvdb::Int32Grid& labels, const std::vector<Coord>& cells, int top,
                                 int farTop, const MergeRule& rule, const openvdb::BoolGrid& near) {
    const std::vector<std::pair<Coord, std::int32_t>> byBlock = cellsByBlock(cells, farTop);
    std::vector<std::size_t> groupStart;
    for (std::size_t i = 0; i < byBlock.size(); ++i)
        if (i == 0 || byBlock[i].first != byBlock[i - 1].first) groupStart.push_back(i);
    groupStart.push_back(byBlock.size());
    std::vector<std::vector<Block>> chosen(groupStart.size() - 1);
    tbb::parallel_for(std::size_t(0), chosen.size(), [&](std::size_t g) {
        const auto acc = labels.getConstAccessor();
        std::vector<std::int32_t> members;
        for (std::size_t i = groupStart[g]; i < groupStart[g + 1]; ++i) members.push_back(byBlock[i].second);
        const Coord lo = byBlock[groupStart[g]].first;
        chooseAwayFromTeeth(windowOf(acc, lo, farTop, rule), cells, lo, farTop, top, rule, near, std::move(members), chosen[g]);
    });
    std::vector<Block> blocks;
    for (auto& v : chosen)
        for (Block& b : v) blocks.push_back(std::move(b));
    return blocks;
}


}  // namespace jawmesh::adaptive
