// The whole job for one jaw: case surfaces -> level sets -> carved label field -> interface complex
// -> labeled tets -> validation -> files in the output layout of docs/DESIGN.md, plus run.json.
// Only wiring: every step is a stage-library function; this file decides order, options and files.
#pragma once

#include "cli/RunOptions.h"
#include "io/Case.h"
#include "io/Progress.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace jawmesh {

/// The input level sets of one jaw, grids named after their labels.
struct JawLevelSets {
    openvdb::FloatGrid::Ptr bone;
    std::map<int, openvdb::FloatGrid::ConstPtr> teeth;  ///< by UNN
};

/// meshToLevelSet of the bone and every tooth of `surfaces` (read from `jawCase`). Throws Error
/// naming the input file for a surface that cannot become a level set (e.g. only degenerate
/// triangles: a point cloud) and for two teeth sharing more than 30% of the smaller one's volume
/// (levelset/InsideOverlap.h: a tooth exported twice, teeth merged). Throws Cancelled.
JawLevelSets jawLevelSets(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm, double bandVoxels,
                          Progress& progress = noProgress());

/// The input file of tooth `unn` of a jaw case, for messages ("<all_teeth.obj> (tooth 24)" when
/// the teeth came from one file).
std::string toothSource(const JawCase& jawCase, int unn);

/// Throws Error naming the tooth's file when a carved tooth got no PDL: it does not reach the bone
/// (a tooth in another coordinate frame, of the other jaw, or far from its socket). runJaw calls it
/// after carving, before the long surface and TetGen stages that would end in a missing PDL.
void requireBoneContact(const CarveSummary& summary, const JawCase& jawCase, const CarveOptions& options);

/// Runs every stage for one jaw and writes <outJawDir>/{volumetric_meshes,surface_meshes,levelsets}
/// and <outJawDir>/run.json. The mesh is validated before anything of it is written; a violation is
/// an Error. Returns the run record written to run.json.
/// Throws Error for bad input or a failed stage, Cancelled when progress is cancelled.
nlohmann::json runJaw(const JawCase& jawCase, const RunOptions& options, const std::string& outJawDir,
                      Progress& progress = noProgress());

/// runJaw into a staging folder (io/StagedFolder.h) moved to outJawDir only when the run is
/// complete: a failed or interrupted run leaves nothing in outJawDir but, when TetGen failed, the
/// interface surface in <outJawDir>/failed_surface/ (the message names it). Throws as runJaw.
nlohmann::json runJawStaged(const JawCase& jawCase, const RunOptions& options, const std::string& outJawDir,
                            Progress& progress = noProgress());

/// runJaw keeps the interface surface of a failed TetGen step in <outJawDir>/failed_surface/ and
/// names it in its message. When outJawDir is about to be removed (a staging folder), this moves
/// that folder to keptDir (replacing it) and returns the message naming keptDir instead; returns
/// the message unchanged when there is no such folder.
std::string keepFailedSurface(const std::string& outJawDir, const std::string& keptDir, std::string message);

}  // namespace jawmesh
