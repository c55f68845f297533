// Small components of the label grid are absorbed by the region around them before extraction:
// - pockets of outside enclosed by the jaw (a few voxels of air trapped between bone and PDL at the
//   crest, left by segmentation noise and the carving);
// - fragments of a region cut off from it (a bone voxel between a PDL and the air, a PDL speck
//   beside a crown: the shared mandible's carved grid has ~200 of 1-30 voxels; an edited grid,
//   e.g. a removed tooth, leaves more).
// They have no physical meaning, and once simplified they become closed slivers of a few tiny
// triangles that TetGen cannot mesh reliably (measured: a 4-triangle outside bubble of 8e-7 mm^3
// between bone and PDL 30 stopped a mandible run; a one-voxel bone speck squeezed to 0.01 mm
// between PDL 25 and the air stopped a run of the 2-tooth phantom without tooth 24).
#pragma once

#include "filters/LabelEdges.h"
#include "io/Labels.h"

#include <openvdb/openvdb.h>

#include <cstddef>
#include <vector>

namespace jawmesh {

struct SmallComponentStats {
    std::size_t pockets = 0;         ///< enclosed outside components absorbed
    std::size_t pocketVoxels = 0;
    std::size_t fragments = 0;       ///< region components absorbed
    std::size_t fragmentVoxels = 0;
};

/// Relabels every face-connected component of outside voxels (kOutsideLabel, background included)
/// of at most `maxOutsideVoxels` voxels, i.e. every enclosed pocket that small, and every
/// face-connected component of a region of at most `maxRegionVoxels` voxels, with the other label
/// most common among the component's face neighbours (ties: the smaller label). A region keeps
/// its largest component even when all are small, so no region disappears. Larger enclosed
/// cavities (a canal) are kept. Labels are read before any is changed, so the result does not
/// depend on the visiting order. Deterministic.
/// The voxels it relabels are appended to `relabelled` when given. `edges`, when given, are the
/// label edges of `labels`, sorted (findLabelEdges, updateLabelEdges; else they are searched for).
/// Cost: a flood fill bounded by the limit from the lower voxel of every label edge (sorted).
SmallComponentStats absorbSmallComponents(openvdb::Int32Grid& labels, std::size_t maxOutsideVoxels,
                                          std::size_t maxRegionVoxels,
                                          std::vector<openvdb::Coord>* relabelled = nullptr,
                                          const std::vector<LabelEdge>* edges = nullptr);

}  // namespace jawmesh
