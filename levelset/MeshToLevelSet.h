// Surface mesh -> narrow-band signed distance grid, robust to dirty input. The distance magnitude
// is the exact distance to the nearest triangle on every band voxel (levelset/BandDistance.h);
// the sign does NOT come from OpenVDB's flood fill (which fills cavities and leaks through
// holes) but from winding numbers of the orientation-repaired mesh (levelset/OrientSurface.h):
// every active voxel gets a vote from the exact scanline along each axis
// (levelset/ScanlineWinding.h); lines that pass through holes abstain, and voxels without a
// clear majority ask Embree for more lines in generic directions (levelset/LineWinding.h).
// Inside = winding >= 1, so overlapping shells give their union and inward-oriented inner
// shells stay cavities. Triangles that end up with the same sign on both sides (the inner walls
// of overlapping shells) are then left out of the distance, so the band has no spurious
// near-zero sheet inside the union. Holes of up to kMaxHoleLoopVertices boundary vertices are
// patched first (levelset/CloseHoles.h): winding numbers alone close a hole with a sign jump
// between +-background and no distance band there, which carving cannot read (issue #27).
#pragma once

#include "io/Progress.h"
#include "io/SurfaceMesh.h"
#include "levelset/BandDistance.h"

#include <nlohmann/json.hpp>
#include <openvdb/openvdb.h>

#include <cstddef>

namespace jawmesh {

/// What meshToLevelSet() did, for reports and tests.
struct MeshToLevelSetStats {
    std::size_t inputTriangles = 0;
    std::size_t droppedDegenerate = 0;   ///< zero-area triangles ignored
    std::size_t droppedDuplicate = 0;    ///< repeated triangles ignored
    std::size_t flippedTriangles = 0;    ///< orientation reversed by the repair
    int patches = 0;                     ///< edge-manifold connected patches
    int nestedPatches = 0;               ///< patches inside another (kept by majority orientation)
    std::size_t holesClosed = 0;         ///< hole loops patched (levelset/CloseHoles.h)
    std::size_t holePatchTriangles = 0;  ///< triangles those patches added
    std::size_t holesLeftOpen = 0;       ///< loops too long to patch, chains that do not close
    std::size_t activeVoxels = 0;
    std::size_t crossings = 0;           ///< scanline crossings over the 3 axes
    std::size_t fallbackVoxels = 0;      ///< voxels without a scanline majority (Embree lines asked)
    std::size_t unresolvedVoxels = 0;    ///< still tied after every extra line (taken as outside)
    std::size_t internalTriangles = 0;   ///< same sign on both sides (inner walls of overlapping
                                         ///< shells): the distance ignores them when >= 16
    double secondsOrient = 0, secondsUnsigned = 0, secondsScanlines = 0, secondsSign = 0;
};

/// The stats as `jawmesh levelset --json` reports them: input_triangles, active_voxels, repair
/// {dropped_degenerate, dropped_duplicate, flipped_triangles, patches, nested_patches,
/// holes_closed, hole_patch_triangles, holes_left_open}, sign
/// {crossings, internal_triangles, fallback_voxels, unresolved_voxels} and stage_seconds.
nlohmann::json toJson(const MeshToLevelSetStats& stats);

/// Narrow-band signed distance (mm, negative inside, GRID_LEVEL_SET class, background =
/// halfWidthVoxels * voxelSizeMm) on openvdb::math::Transform::createLinearTransform(voxelSizeMm)
/// (voxel centres at ijk * voxel), so all domains meshed with the same voxel size share one
/// transform. Inactive voxels carry -background inside and +background outside.
/// @param mesh            surface in mm; any triangle soup (holes a few voxels wide, flipped or
///                        mixed orientation, duplicate or zero-area faces, overlapping shells,
///                        cavities, small self-intersections are handled, see the file comment)
/// @param voxelSizeMm     edge of a voxel, > 0
/// @param halfWidthVoxels narrow band half width in voxels, >= 1
/// @throws Error for a non-positive voxel size, a half width below 1, a mesh without triangles or
///         one too large for the voxel size; Cancelled when progress is cancelled.
/// Deterministic: the grid does not depend on the thread count.
/// Cost: about (surface area / voxel^2) * 2 * halfWidth active voxels; the exact band distance is
/// about half the time, orientation, scanlines and sign the rest (docs/BENCHMARKS.md); memory
/// about 10 bytes per active voxel plus the mesh and the scanline crossings.
openvdb::FloatGrid::Ptr meshToLevelSet(const SurfaceMesh& mesh, double voxelSizeMm, double halfWidthVoxels = 3.0,
                                       Progress& progress = noProgress());

/// As above, and fills stats.
openvdb::FloatGrid::Ptr meshToLevelSet(const SurfaceMesh& mesh, double voxelSizeMm, double halfWidthVoxels,
                                       MeshToLevelSetStats& stats, Progress& progress = noProgress());

/// As above with a band of two widths (levelset/BandDistance.h; both at least 1 voxel, boxes in
/// index space: mm / voxelSizeMm); the background is widths.halfWidthVoxels * voxelSizeMm.
openvdb::FloatGrid::Ptr meshToLevelSet(const SurfaceMesh& mesh, double voxelSizeMm, const BandWidths& widths,
                                       MeshToLevelSetStats& stats, Progress& progress = noProgress());

}  // namespace jawmesh
