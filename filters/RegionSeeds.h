// One interior point per connected component of every region of a label grid: what TetGen needs
// to label its tetrahedra (region attributes).
#pragma once

#include "io/InterfaceComplex.h"
#include "io/Progress.h"

#include <openvdb/openvdb.h>

#include <map>
#include <vector>

namespace jawmesh {

/// For every region label L != kOutsideLabel of `labels` and every face-connected component of its
/// voxels (tiles included), the centre (mm, through labels' transform) of the component voxel
/// deepest inside it: the most negative distances[L] value among the voxels whose 26 neighbours
/// all carry L, or among all its voxels when none does (a 1-voxel-thin component). Sorted by
/// (label, point). For a well-composed grid (see WellComposedLabels.h) the point lies strictly
/// inside the region's extracted dual surface.
/// Cost: one connected-component labelling per region (OpenVDB segmentActiveVoxels).
std::vector<RegionSeed> findRegionSeeds(const openvdb::Int32Grid& labels,
                                        const std::map<Label, openvdb::FloatGrid::Ptr>& distances,
                                        Progress& progress = noProgress());

}  // namespace jawmesh
