// Small pockets of outside enclosed by the jaw (a few voxels of air trapped between bone and PDL at
// the crest, left by segmentation noise and the carving) are filled with their surrounding region.
// They have no physical meaning, and once simplified they become closed slivers of a few tiny
// triangles that TetGen cannot mesh reliably (measured on the shared mandible: a 4-triangle outside
// bubble of 8e-7 mm^3 between bone and PDL 30 stopped the run).
#pragma once

#include "io/Labels.h"

#include <openvdb/openvdb.h>

#include <cstddef>

namespace jawmesh {

struct EnclosedOutsideStats {
    std::size_t pockets = 0;  ///< enclosed components filled
    std::size_t voxels = 0;   ///< voxels relabelled
};

/// Relabels every face-connected component of outside voxels (kOutsideLabel, background included)
/// that no face path of outside voxels joins to a component of more than `maxVoxels` voxels, i.e.
/// every enclosed pocket smaller than that, with the region most common among the pocket's face
/// neighbours (ties: the smaller label). Larger enclosed cavities (a canal) are kept.
/// Deterministic. Cost: a bounded flood fill from every outside voxel next to a region.
EnclosedOutsideStats fillEnclosedOutside(openvdb::Int32Grid& labels, std::size_t maxVoxels);

}  // namespace jawmesh
