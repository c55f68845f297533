// Where the labels of a LabelField change: the pairs of face-adjacent voxels with different labels
// ("label edges", primal edges between voxel centres), and the dual cells around them (2x2x2
// blocks of voxels, named by their lowest corner). Shared by the well-composed repair and by
// interface extraction, so both see exactly the same interfaces.
#pragma once

#include "io/Labels.h"

#include <openvdb/openvdb.h>

#include <map>
#include <vector>

namespace jawmesh {

/// Voxel `voxel` and voxel + e_axis have different labels.
struct LabelEdge {
    openvdb::Coord voxel;
    int axis;  ///< 0 = x, 1 = y, 2 = z
};

/// All label edges, sorted by (voxel, axis). Only voxels that can lie next to a label change are
/// visited: the voxels of the label tree's leaf nodes and the active (narrow-band) voxels of the
/// distance grids. A label change between two tiles away from every distance band (which the
/// LabelField contract excludes: labels agree with the distance signs) would be missed.
/// Deterministic; parallel over leaf nodes. Cost: O(visited voxels).
std::vector<LabelEdge> findLabelEdges(const openvdb::Int32Grid& labels,
                                      const std::map<Label, openvdb::FloatGrid::Ptr>& distances);

/// Sorted, unique lowest corners of the dual cells (2x2x2 voxel blocks) that contain a label edge:
/// for edge (v, axis) these are v - a e1 - b e2 for a, b in {0, 1}, e1, e2 the other two axes.
std::vector<openvdb::Coord> dualCellsOf(const std::vector<LabelEdge>& edges);

/// Index of cell c in the sorted array cells (from dualCellsOf), or -1.
std::int64_t dualCellIndex(const std::vector<openvdb::Coord>& cells, const openvdb::Coord& c);

/// Corner k (0..7, bit 0 = +x, bit 1 = +y, bit 2 = +z) of the dual cell with lowest corner c.
inline openvdb::Coord dualCellCorner(const openvdb::Coord& c, int k) {
    return c.offsetBy(k & 1, (k >> 1) & 1, (k >> 2) & 1);
}

}  // namespace jawmesh
