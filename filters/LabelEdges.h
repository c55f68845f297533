// Where the labels of a LabelField change: the pairs of face-adjacent voxels with different labels
// ("label edges", primal edges between voxel centres), and the dual cells around them (2x2x2
// blocks of voxels, named by their lowest corner). Shared by the well-composed repair and by
// interface extraction, so both see exactly the same interfaces.
#pragma once

#include "io/Labels.h"

#include <openvdb/openvdb.h>

#include <vector>

namespace jawmesh {

/// Voxel `voxel` and voxel + e_axis have different labels.
struct LabelEdge {
    openvdb::Coord voxel;
    int axis;  ///< 0 = x, 1 = y, 2 = z
};

/// All label edges, sorted by (voxel, axis). Only voxels that can lie next to a label change are
/// visited: the voxels of the label tree's leaf nodes (each looks at its six neighbours) and the
/// faces of label tiles that border a tile of another label or the background. Any other change
/// is between two voxels outside the leaves, so between two tiles, or a tile and the background:
/// a repaired level set's sign can jump between inactive values with no band (across a hole in the
/// input surface that the winding numbers closed), and a change missed there was a hole in the
/// extracted surface. (The distance grids' bands were visited too until session 39: they added 10 %
/// of the leaves of the shared mandible and no edge.)
/// Deterministic; parallel over leaf nodes. Cost: O(visited voxels).
std::vector<LabelEdge> findLabelEdges(const openvdb::Int32Grid& labels);

/// `edges` (findLabelEdges of `labels` before the voxels `changed` were relabelled) made the label
/// edges of `labels` now: the six edges at each of those voxels looked at again, the rest kept.
/// What a new search finds, since a relabelled voxel sits in a leaf of `labels` (where the search
/// looks), and far cheaper for the few voxels a repair changes. Cost: O(edges + changed log changed).
void updateLabelEdges(std::vector<LabelEdge>& edges, const openvdb::Int32Grid& labels,
                      const std::vector<openvdb::Coord>& changed);

/// Sorted, unique lowest corners of the dual cells (2x2x2 voxel blocks) that contain a label edge:
/// for edge (v, axis) these are v - a e1 - b e2 for a, b in {0, 1}, e1, e2 the other two axes.
std::vector<openvdb::Coord> dualCellsOf(const std::vector<LabelEdge>& edges);

/// Index of cell c in the sorted array cells (from dualCellsOf), or -1, searched outward from
/// position `hint` (any index, e.g. the answer for the previous of a sequence of nearby cells),
/// then updated to where c is or would be: O(log distance) instead of O(log n) for look-ups in
/// sorted order (the quads of the sorted edges).
std::int64_t dualCellIndex(const std::vector<openvdb::Coord>& cells, const openvdb::Coord& c, std::size_t& hint);

/// Corner k (0..7, bit 0 = +x, bit 1 = +y, bit 2 = +z) of the dual cell with lowest corner c.
inline openvdb::Coord dualCellCorner(const openvdb::Coord& c, int k) {
    return c.offsetBy(k & 1, (k >> 1) & 1, (k >> 2) & 1);
}

}  // namespace jawmesh
