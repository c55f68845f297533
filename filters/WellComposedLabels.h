// Removes diagonal-only contacts from a label grid, so that the dual surface of every region is a
// 2-manifold with one vertex per dual cell. A region is "well-composed" when no 2x2x2 block of
// voxels shows one of the two critical configurations for it: the region on one diagonal of a
// block face and absent from the other diagonal, or the region on exactly two opposite corners of
// the block (or absent from exactly two opposite corners). Each such block is fixed by relabelling
// one voxel, and the scan repeats until no block is critical.
//
// Choice made (documented in docs/): every fix raises one voxel to a region of strictly higher
// priority (PDL > tooth > bone > outside; ties: smaller label), which guarantees termination.
// A region seen on a diagonal is joined through a separating voxel of lower priority when there is
// one (a 1-voxel PDL sheet with diagonal steps is thickened by a voxel there and stays connected;
// two bone voxels touching across an outside edge are joined); when all separating voxels rank
// higher, one of its two voxels is given to the highest-ranked neighbouring region instead (the
// contact is cut). Candidate voxels are ranked by lowest priority, then shallowest (largest own
// signed distance), then lowest coordinate, so the result is deterministic.
#pragma once

#include "filters/LabelEdges.h"
#include "io/Labels.h"
#include "io/Progress.h"

#include <openvdb/openvdb.h>

#include <map>
#include <vector>

namespace jawmesh {

/// Relative importance of keeping a region connected across a diagonal contact (higher wins).
int labelConnectPriority(Label label);

/// Relabels voxels of `labels` in place until every region is well-composed; returns the number of
/// voxels relabelled. `distances` (may be empty) breaks ties between candidate voxels.
/// Throws Error if the repair does not converge within 256 sweeps (not seen in the tests, random
/// labels included).
/// With `changedVoxels`, the labels were well-composed before those voxels changed, so only the
/// dual cells around them are looked at.
/// Cost: one findLabelEdges (none with changedVoxels), then O(cells looked at) per sweep; usually
/// 1-3 sweeps.
/// The voxels it relabels are appended to `relabelled` when given (each once per sweep).
std::size_t makeLabelsWellComposed(openvdb::Int32Grid& labels,
                                   const std::map<Label, openvdb::FloatGrid::Ptr>& distances,
                                   Progress& progress = noProgress(),
                                   const std::vector<openvdb::Coord>* changedVoxels = nullptr,
                                   std::vector<openvdb::Coord>* relabelled = nullptr);

/// The same, with the label edges of `labels` (findLabelEdges) given: none is searched for.
std::size_t makeLabelsWellComposed(openvdb::Int32Grid& labels,
                                   const std::map<Label, openvdb::FloatGrid::Ptr>& distances,
                                   const std::vector<LabelEdge>& edges, Progress& progress,
                                   std::vector<openvdb::Coord>* relabelled);

/// Number of voxels one repair sweep would relabel (0 when every region is well-composed).
std::size_t countCriticalCells(const openvdb::Int32Grid& labels,
                               const std::map<Label, openvdb::FloatGrid::Ptr>& distances);

}  // namespace jawmesh
