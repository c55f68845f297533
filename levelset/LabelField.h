// The carved jaw as grids: one sparse label grid plus the signed distance field of every region,
// all on the same transform (voxel size in mm, cell-centred index space). Output of carving
// (levelset/), input of interface-surface extraction (filters/). Written and read back as .vdb so
// a user can edit a grid and resume (see docs/).
#pragma once

#include "io/Labels.h"

#include <openvdb/openvdb.h>

#include <map>

namespace jawmesh {

struct LabelField {
    double voxelSizeMm = 0.0;
    Jaw jaw = Jaw::Mandible;
    /// labels->tree().getValue(ijk) is the region of voxel ijk for every ijk (active or not, tiles
    /// included); the background is kOutsideLabel. Regions are bone, toothLabel(unn), pdlLabel(unn).
    openvdb::Int32Grid::Ptr labels;
    /// Narrow-band signed distance (mm, negative inside, level-set class) of each region present in
    /// labels, consistent with it: a voxel has label L exactly where distances[L] < 0, up to ties
    /// resolved by the carving rules. Used for sub-voxel placement of interfaces downstream.
    std::map<Label, openvdb::FloatGrid::Ptr> distances;
};

}  // namespace jawmesh
