// The level-set stage of one jaw: its bone and every tooth become narrow-band signed distances
// (levelset/MeshToLevelSet.h) on one transform, and teeth that share much of their volume (a tooth
// exported twice, two teeth segmented into each other) are refused before carving hides it.
#pragma once

#include "io/Case.h"
#include "io/Progress.h"

#include <openvdb/openvdb.h>

#include <map>

namespace jawmesh {

/// The input level sets of one jaw, grids named after their labels.
struct JawLevelSets {
    openvdb::FloatGrid::Ptr bone;
    /// By UNN; an implant in place of a tooth (CarveOptions::implants) is carved as one with no PDL.
    std::map<int, openvdb::FloatGrid::ConstPtr> teeth;
};

/// meshToLevelSet of the bone and every tooth of `surfaces` (read from `jawCase`), band half widths
/// in voxels: the teeth's the wider of the bone's and toothBandVoxels (what carving reads of them:
/// levelset/CarveGaps.h toothBandVoxels); the bone's boneBandVoxels within kBoneWideBandMarginMm
/// of a tooth's bounding box (carving extends the bone's distance only within about 1 mm of a
/// tooth) and boneFarBandVoxels (at most boneBandVoxels) elsewhere. Throws Error
/// naming the input file for a surface that cannot become a level set (e.g. only degenerate
/// triangles: a point cloud) and for two teeth sharing more than 30% of the smaller one's volume
/// (levelset/InsideOverlap.h: a tooth exported twice, teeth merged). Throws Cancelled.
JawLevelSets jawLevelSets(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm, double boneBandVoxels,
                          double boneFarBandVoxels, double toothBandVoxels, Progress& progress = noProgress());

/// Around each tooth's bounding box, how far the bone keeps its full band (mm). The edits
/// (levelset/JawEdits.h) all act at an input tooth (its socket, its crest), so inside these boxes;
/// an edit placed away from every tooth would need its site added to them.
constexpr double kBoneWideBandMarginMm = 2.0;

}  // namespace jawmesh
