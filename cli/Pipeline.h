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
