// A surface as a segmentation leaves it before any smoothing (issue #27 item 3): the voxels of its
// inside at a given size, extracted as they are, so every face is a voxel step.
#pragma once

#include "io/SurfaceMesh.h"
#include "levelset/LevelSetSurface.h"
#include "levelset/MeshToLevelSet.h"

#include <openvdb/openvdb.h>
#include <openvdb/tree/LeafManager.h>

namespace jawmesh::test {

/// The surface's level set at voxelMm made binary (+-0.5 voxel: inside or not), extracted: an
/// unsmoothed voxel staircase of the closed surface `m`.
inline SurfaceMesh voxelStaircase(const SurfaceMesh& m, double voxelMm) {
    const openvdb::FloatGrid::Ptr grid = meshToLevelSet(m, voxelMm, 3.0);
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid->tree());
    leaves.foreach([](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
        for (auto v = leaf.beginValueOn(); v; ++v) v.setValue(*v < 0 ? -0.5f : 0.5f);
    });
    return extractLevelSetSurface(*grid, 0.0);
}

}  // namespace jawmesh::test
