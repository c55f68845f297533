// A label field whose labels change between tiles of the label tree, away from any leaf node or
// distance band, as a repaired level set leaves them where its sign jumps without a band (winding
// numbers closing a hole in a bone surface, overlapping tooth shells). Interface extraction missed
// such changes, and the holes they left in the surface made the tet stage fail (issue #27).
#pragma once

#include "io/Labels.h"
#include "levelset/LabelField.h"

namespace jawmesh::test {

/// A bone slab 32 x 16 x 16 voxels of 0.05 mm stored as tiles, only its x < 16 half as leaf nodes,
/// and a tooth 24 tile (8 voxels on a side) against its x = 32 end; no distance grids.
inline LabelField tiledSlabField() {
    LabelField f;
    f.voxelSizeMm = 0.05;
    f.labels = openvdb::Int32Grid::create(kOutsideLabel);
    f.labels->setTransform(openvdb::math::Transform::createLinearTransform(f.voxelSizeMm));
    auto& tree = f.labels->tree();
    tree.fill(openvdb::CoordBBox({0, 0, 0}, {31, 15, 15}), kMandibleBoneLabel, true);
    tree.fill(openvdb::CoordBBox({32, 0, 0}, {39, 7, 7}), toothLabel(24), true);
    for (int y = 0; y < 16; y += 8)
        for (int z = 0; z < 16; z += 8)
            for (int x = 0; x < 16; x += 8) tree.touchLeaf(openvdb::Coord(x, y, z));
    return f;
}

}  // namespace jawmesh::test
