// Blocks of dual cells that one surface-nets vertex may stand for (the coarse cells of the adaptive
// extraction, filters/AdaptiveCells.h).
//
// A block of level L is the cube of 2^L x 2^L x 2^L dual cells whose lowest cell is a multiple of
// 2^L; it spans the closed voxel cube [lo, lo + 2^L]^3, and neighbouring blocks share the voxels of
// their common face. Merging all of a block's dual-cell vertices into one vertex keeps the surface a
// manifold of the same topology when the fine interface inside the block is one disc that meets
// every face of the block in at most one arc and every edge of the block at most once: the disc
// contracts to a point, each face arc to an edge (octree dual contouring's topological safety, Ju et
// al. 2002, stated on the voxels themselves instead of recursively). blockIsOneDisc tests exactly
// that, on the labels alone:
//  - the block's voxels carry exactly two labels, both among its 8 corners, a pair the caller allows;
//  - along each of the 12 edges the label changes at most once;
//  - on each of the 6 faces the label changes at most twice around the border and each label's
//    voxels are 4-connected (one arc, no island);
//  - each label's corners are connected along the cube's edges (one loop around the cube);
//  - in the block each label's voxels are 6-connected with Euler characteristic 1 (a ball: no
//    tunnel, no cavity), so the interface between them is a disc.
//
// A layer (blockIsLayer) is a block that two parallel sheets cross, such as the two sides of a
// periodontal ligament 4 voxels thick, which no block of level 2 or more can avoid: three labels,
// the two outer ones never closer than minGapVoxels voxels of the middle one (so no dual cell holds
// both sheets, and the layer is no thin plate), and each outer label against the other two passes
// the tests above, so each sheet (outer | middle) is one disc. Each sheet's cells can then merge
// into a vertex of their own: two disjoint vertex identifications.
#pragma once

#include "io/Labels.h"

#include <openvdb/openvdb.h>

#include <array>
#include <functional>
#include <optional>
#include <vector>

namespace jawmesh {

/// The labels of a cube of voxels copied once, for the many overlapping cubes a block and its
/// children are tested on (reading them through the grid each time was a twelfth of the extraction).
/// Voxels outside the cube are read from the grid.
class LabelWindow {
public:
    /// The cube [lo, lo + n - 1]^3.
    LabelWindow(const openvdb::Int32Grid::ConstAccessor& labels, const openvdb::Coord& lo, int n);
    Label at(const openvdb::Coord& c) const {
        const openvdb::Coord d = c - lo_;
        if (unsigned(d.x()) < unsigned(n_) && unsigned(d.y()) < unsigned(n_) && unsigned(d.z()) < unsigned(n_))
            return dense_[std::size_t((d.z() * n_ + d.y()) * n_ + d.x())];
        return labels_.getValue(c);
    }

private:
    const openvdb::Int32Grid::ConstAccessor& labels_;
    openvdb::Coord lo_;
    int n_;
    std::vector<Label> dense_;
};

/// The two labels of the closed voxel cube [lo, lo + size]^3 when their interface there is one disc
/// as described above and `allowed` accepts the pair (called with the smaller label first); empty
/// otherwise. 1 <= size <= 63. Cost: O(size^3) label reads.
std::optional<std::array<Label, 2>> blockIsOneDisc(const LabelWindow& labels, const openvdb::Coord& lo, int size,
                                                   const std::function<bool(Label, Label)>& allowed);

struct BlockLayer {
    std::array<Label, 2> outer;  ///< the labels on either side of the layer, smaller first
    Label middle = 0;            ///< the layer's own label
};

/// The layer of the closed voxel cube [lo, lo + size]^3 as described above, or empty; size <= 63. Cost:
/// O(size^3 minGapVoxels) label reads and mask operations.
std::optional<BlockLayer> blockIsLayer(const LabelWindow& labels, const openvdb::Coord& lo,
                                       int size, int minGapVoxels);

}  // namespace jawmesh
