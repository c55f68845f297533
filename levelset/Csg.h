// Boolean and morphological operations on narrow-band level sets (openvdb::FloatGrid, mm, negative
// inside). Every function takes its inputs by const reference and returns a new grid: inputs are
// never modified or emptied (unlike openvdb::tools::csgUnion, which empties its second argument).
// All grids involved must share one transform (same voxel size and origin); otherwise Error.
//
// Accuracy: union / intersection / difference are min / max of the inputs, exact on the zero set
// and equal to the true signed distance away from creases. offset / close / open / renormalize
// rebuild the band from the iso-surface (OpenVDB's volume -> mesh -> distance, i.e. the
// "sdf -> surface -> sdf" route). OpenVDB's distances are exact only within ~2 voxels of the
// surface (up to ~0.5 voxel off beyond: its band expansion reuses neighbours' closest triangles),
// so the band beyond 2 voxels is recomputed by closest-point propagation (as in
// extendExteriorDistance): errors about a tenth of a voxel on smooth shapes, whatever the width of
// the input band.
#pragma once

#include "io/Progress.h"

#include <openvdb/openvdb.h>

namespace jawmesh {

/// Union a ∪ b (min of the two fields) as a new grid with a's transform and background.
/// Throws Error if the transforms differ. Cost: linear in the active voxels of a and b.
openvdb::FloatGrid::Ptr csgUnion(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b);

/// Intersection a ∩ b (max of the two fields) as a new grid. Same contract as csgUnion.
openvdb::FloatGrid::Ptr csgIntersection(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b);

/// Difference a \ b (max(a, -b)) as a new grid. Same contract as csgUnion.
openvdb::FloatGrid::Ptr csgDifference(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b);

/// Re-normalises a level set: a new grid holding the true signed distance (mm) to the zero
/// iso-surface of `grid`, in a band of `exteriorHalfWidthVoxels` outside and
/// `interiorHalfWidthVoxels` inside (also how a band is widened). Interior is marked by negative
/// inactive tiles as usual. Throws Error for a grid that is not a level set on a uniform transform.
/// Cost: one polygonisation + one exact mesh-to-distance pass over the band (TBB); memory of the
/// order of the output band.
openvdb::FloatGrid::Ptr renormalizeLevelSet(const openvdb::FloatGrid& grid,
                                            double exteriorHalfWidthVoxels = 3.0,
                                            double interiorHalfWidthVoxels = 3.0,
                                            Progress& progress = noProgress());

/// Offsets a level set by distanceMm: positive dilates (the surface moves outward), negative
/// erodes. The input band may be narrower than |distanceMm|: it is widened first. The result is
/// a true signed distance field with the given half width on each side.
/// Throws Error for a non-finite distance or mismatched grids. Cost: one or two re-normalisations.
openvdb::FloatGrid::Ptr offsetLevelSet(const openvdb::FloatGrid& grid, double distanceMm,
                                       double halfWidthVoxels = 3.0,
                                       Progress& progress = noProgress());

/// Morphological closing by a ball of radiusMm (dilate then erode): fills gaps, pits and concave
/// corners narrower than 2 * radiusMm; convex parts are unchanged. Cost: two offsets.
openvdb::FloatGrid::Ptr closeLevelSet(const openvdb::FloatGrid& grid, double radiusMm,
                                      double halfWidthVoxels = 3.0, Progress& progress = noProgress());

/// Morphological opening by a ball of radiusMm (erode then dilate): removes spikes, thin plates
/// and bridges thinner than 2 * radiusMm. Cost: two offsets.
openvdb::FloatGrid::Ptr openLevelSet(const openvdb::FloatGrid& grid, double radiusMm,
                                     double halfWidthVoxels = 3.0, Progress& progress = noProgress());

/// Exterior distances beyond the band of a level set, computed only where they are needed: for every
/// voxel of `region` that lies outside the surface of `grid` and is reachable from the band through
/// region voxels, the Euclidean distance (mm) to the zero set of `grid`, up to maxDistanceMm.
/// Method: closest-point propagation (a vector distance transform). The band voxels of grid with
/// background - 2 voxels <= value <= background - 1 voxel, in leaves that region touches, are seeds
/// whose closest surface point is x - value * grad / |grad|; voxels are then settled in order of
/// distance (Dijkstra-like, 26-neighbourhood, ties broken by coordinate, so the result does not
/// depend on anything but the inputs), each taking the nearest of the closest points offered by its
/// settled neighbours. Errors: about a quarter of a voxel next to the band, less farther out, on
/// smooth surfaces (enough to decide gaps; not a substitute for an exact band).
/// @param grid           level set (band >= 2 voxels for accurate seeds), not modified
/// @param region         voxels where distances are wanted (leaf voxels; tiles are ignored)
/// @param maxDistanceMm  propagation stops beyond this distance
/// @returns a grid on grid's transform whose active voxels are the computed voxels outside the band
///          of grid (band voxels keep their own, exact values in grid); background maxDistanceMm.
/// Throws Error for a grid that is not a level set. Cost: serial, O(n log n) in the region voxels
/// reached plus the seeds (26 neighbour look-ups each); call it on several grids in parallel.
openvdb::FloatGrid::Ptr extendExteriorDistance(const openvdb::FloatGrid& grid, const openvdb::MaskTree& region,
                                               double maxDistanceMm);

/// The same inside the surface: for every voxel of `region` inside the surface of `grid`, off its
/// band and reachable from it through region voxels, minus the distance (mm) to the zero set, down
/// to -maxDistanceMm (only the active voxels hold values; the background is +maxDistanceMm). Same
/// method, errors, determinism and cost as extendExteriorDistance.
openvdb::FloatGrid::Ptr extendInteriorDistance(const openvdb::FloatGrid& grid, const openvdb::MaskTree& region,
                                               double maxDistanceMm);

/// A copy of a level set whose exterior distances reach reachMm: the band, and beyond it
/// extendExteriorDistance over the voxels within reach (same errors); the background becomes
/// reachMm (inactive values +-reachMm). What a dilation needs when only its sign and the distance
/// near its surface matter, at a fraction of offsetLevelSet's cost. Throws as extendExteriorDistance.
openvdb::FloatGrid::Ptr withExteriorReach(const openvdb::FloatGrid& grid, double reachMm);

/// Half width of the band of a level set in mm (its background value). Throws Error when the grid
/// has a non-positive background (not a level set).
double bandHalfWidthMm(const openvdb::FloatGrid& grid);

/// Voxel size (mm) of a grid on a uniform linear transform; throws Error otherwise.
double uniformVoxelSizeMm(const openvdb::FloatGrid& grid);

/// Throws Error("<what>: ...") unless a and b share one transform.
void requireSameTransform(const openvdb::GridBase& a, const openvdb::GridBase& b, const char* what);

}  // namespace jawmesh
