// From an implicit function to a segmentation-like surface (helper of Phantom.h): sample the
// function into a narrow-band level set, extract it with OpenVDB's volumeToMesh (quads split along
// their shorter diagonal, levelset/LevelSetSurface.h), then move vertices tangentially at random so the triangulation looks
// like marching cubes plus smoothing rather than a clean grid.
#pragma once

#include "io/Progress.h"
#include "io/SurfaceMesh.h"

#include <openvdb/openvdb.h>

#include <cstdint>
#include <functional>

namespace jawmesh::phantom {

/// Samples `field` (mm, negative inside, Lipschitz constant at most `lipschitz`) on a grid of
/// voxel size voxelMm (index (i,j,k) at world (i,j,k) * voxelMm) over `box`, as a level set with a
/// narrow band of 3 voxels each side; leaves farther from the zero set are skipped by testing the
/// field at their centre, and the inside is filled by signed flood fill. The zero set must lie
/// inside `box`. Deterministic regardless of the thread count (TBB over leaves).
/// Cost: one field evaluation per 8^3 block of the box plus about one per voxel within a few
/// voxels of the zero set (sub-blocks farther away are skipped by the same test).
openvdb::FloatGrid::Ptr sampleLevelSet(const std::function<double(const Vec3&)>& field, const BBox& box,
                                       double voxelMm, double lipschitz = 1.5);

/// Moves each vertex by a random tangential offset of at most amplitudeMm (tangent plane of the
/// area-weighted vertex normal); a move that would turn any incident triangle by more than 60
/// degrees is halved, then dropped. Sequential, deterministic for a given seed. Cost: O(triangles).
void jitterTangentially(SurfaceMesh& mesh, double amplitudeMm, std::uint64_t seed);

}  // namespace jawmesh::phantom
