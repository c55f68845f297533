// Closest-point propagation: distances to a level set's zero set carried off its narrow band, the
// engine of extendExteriorDistance / extendInteriorDistance and of the band repair after a
// rebuild (levelset/Csg.h documents what those guarantee).
//
// Method: seeds are band voxels whose closest surface point is x - value * grad / |grad|; voxels
// are then settled in order of distance (Dijkstra-like, 26-neighbourhood, ties broken by
// coordinate, so the result depends on nothing but the inputs), each taking the nearest of the
// closest points offered by its settled neighbours. The work is kept in flat arrays per leaf of the
// region (offers, the voxels that may take one, the band) found through a dense table of the
// region's leaves: a settled voxel looks at 26 neighbours, and OpenVDB accessors with one cached
// leaf spent most of the time on those look-ups.
#pragma once

#include <openvdb/openvdb.h>

namespace jawmesh {

/// Propagation on the side `side` (+1 outside, -1 inside) of `grid`, seeded by the voxels of
/// grid's leaves at region leaves with seedLowMm <= side * value <= seedHighMm, into region voxels
/// with side * value > max(seedLowMm, 0), up to maxDistanceMm. Writes side * distance (mm) for the
/// voxels settled off the band, and for band voxels too when withBand; background maxDistanceMm.
/// A thin seed shell is several times cheaper than the whole band (every path leaving the band
/// crosses it) but less accurate near the shell (~0.25 voxel instead of ~0.12).
/// Cost: serial, O(n log n) in the voxels reached; memory about 2.2 KB per leaf of the region and
/// 4 bytes per leaf of the region's bounding box.
openvdb::FloatGrid::Ptr propagateClosestPoints(const openvdb::FloatGrid& grid, const openvdb::MaskTree& region,
                                               double maxDistanceMm, double seedLowMm, double seedHighMm, int side,
                                               bool withBand);

}  // namespace jawmesh
