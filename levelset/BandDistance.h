// Exact unsigned distance to a triangle set on the voxels of a narrow band, computed leaf by leaf:
// every triangle is bucketed into the 8^3 leaf nodes its band-widened bounding box reaches (leaves
// beyond the band from its plane skipped), then each leaf takes, per voxel, the minimum of the
// exact point-triangle distances, with a cheap lower bound (distance to the triangle's plane and
// to the half-plane of its farthest edge) rejecting most pairs before the exact test. A leaf's
// values depend only on its own triangles, so the result is the same whatever the thread count.
// This replaces OpenVDB's unsigned mesh-to-volume in meshToLevelSet(), which spent minutes on a
// real bone (voxelize, then approximate band expansion one voxel per pass).
#pragma once

#include "io/Progress.h"
#include "io/SurfaceMesh.h"

#include <openvdb/openvdb.h>

#include <vector>

namespace jawmesh {

/// Unsigned distance (mm) from every voxel centre to the nearest of the triangles, on the voxels
/// closer than halfWidthVoxels; those voxels are active, every other value is the background
/// halfWidthVoxels * voxelSizeMm. Exact up to float rounding (about 1e-6 voxel).
/// @param indexVertices   vertex positions in index space (mm / voxelSizeMm): voxel centres are
///                        the integer points
/// @param triangles       indices into indexVertices; zero-area triangles are measured as their
///                        edges, so any soup is accepted
/// @param voxelSizeMm     edge of a voxel, > 0 (only scales the stored values)
/// @param halfWidthVoxels band half width in voxels, > 0
/// @returns a tree of leaf nodes only (no tiles), background as above.
/// @throws Cancelled when progress is cancelled.
/// Deterministic. Cost: about (triangle count) * (triangle size + 2 halfWidth)^3 cheap bound
/// tests plus the band volume times the triangles within reach of a voxel exact tests, parallel
/// over columns of leaves; memory: the leaves plus 8 bytes per (triangle, leaf) pair.
openvdb::FloatTree::Ptr bandDistance(const std::vector<Vec3>& indexVertices, const std::vector<Tri>& triangles,
                                     double voxelSizeMm, double halfWidthVoxels, Progress& progress = noProgress());

/// A band of two widths: halfWidthVoxels on the voxels of wideBoxes, farHalfWidthVoxels (at most
/// halfWidthVoxels) everywhere else. For a surface of which only part needs the wide band (the
/// bone, whose distance carving reads far off its surface only around the teeth): the cost of the
/// band grows with its width.
struct BandWidths {
    double halfWidthVoxels = 3.0;
    double farHalfWidthVoxels = 3.0;
    std::vector<openvdb::CoordBBox> wideBoxes;  ///< index space (voxel coordinates)
};

/// bandDistance above with the widths of `widths`: a voxel is active when it is closer than the
/// width at it; the background is halfWidthVoxels * voxelSizeMm. The same values as the uniform
/// band on the voxels both keep (each voxel meets every triangle within its width).
openvdb::FloatTree::Ptr bandDistance(const std::vector<Vec3>& indexVertices, const std::vector<Tri>& triangles,
                                     double voxelSizeMm, const BandWidths& widths, Progress& progress = noProgress());

}  // namespace jawmesh
