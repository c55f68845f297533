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
#pragma once

#include "io/Labels.h"

#include <openvdb/openvdb.h>

#include <array>
#include <functional>
#include <optional>

namespace jawmesh {

/// The two labels of the closed voxel cube [lo, lo + size]^3 when their interface there is one disc
/// as described above and `allowed` accepts the pair (called with the smaller label first); empty
/// otherwise. size >= 1. Cost: O(size^3) label reads.
std::optional<std::array<Label, 2>> blockIsOneDisc(const openvdb::Int32Grid::ConstAccessor& labels,
                                                   const openvdb::Coord& lo, int size,
                                                   const std::function<bool(Label, Label)>& allowed);

}  // namespace jawmesh
