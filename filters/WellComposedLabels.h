// Removes diagonal-only contacts from a label grid, so that the dual surface of every region is a
// 2-manifold with one vertex per dual cell. A region is "well-composed" when no 2x2x2 block of
// voxels shows one of the two critical configurations for it: the region on one diagonal of a
// block face and absent from the other diagonal, or the region on exactly two opposite corners of
// the block (or absent from exactly two opposite corners). Each such block is fixed by relabelling
// one voxel, and the scan repeats until no block is critical.
//
// Choice made (documented in docs/): diagonal contacts are *joined*, never cut, except when the
// separating voxels all belong to one region of higher priority, which is then joined instead.
// Priority: PDL > tooth > bone > outside (ties: smaller label). So a 1-voxel PDL sheet with
// diagonal steps stays connected (it is thickened by one voxel there), and two PDL voxels touching
// across a bone/tooth corner are joined. Where a region grows into a voxel, the voxel chosen is the
// one of lowest priority, then the shallowest one (largest own signed distance), then the lowest
// coordinate, so the result is deterministic.
#pragma once

#include "io/Labels.h"
#include "io/Progress.h"

#include <openvdb/openvdb.h>

#include <map>

namespace jawmesh {

/// Relative importance of keeping a region connected across a diagonal contact (higher wins).
int labelConnectPriority(Label label);

/// Relabels voxels of `labels` in place until every region is well-composed; returns the number of
/// voxels relabelled. `distances` (may be empty) breaks ties between candidate voxels.
/// Throws Error if the repair does not converge within 64 sweeps (never seen on real data).
/// Cost per sweep: one findLabelEdges plus O(dual cells); usually 1-3 sweeps.
std::size_t makeLabelsWellComposed(openvdb::Int32Grid& labels,
                                   const std::map<Label, openvdb::FloatGrid::Ptr>& distances,
                                   Progress& progress = noProgress());

/// Number of voxels one repair sweep would relabel (0 when every region is well-composed).
std::size_t countCriticalCells(const openvdb::Int32Grid& labels,
                               const std::map<Label, openvdb::FloatGrid::Ptr>& distances);

}  // namespace jawmesh
