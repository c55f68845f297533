// The whole job for one jaw: case surfaces -> level sets -> carved label field -> interface complex
// -> labeled tets -> validation -> files in the output layout of docs/DESIGN.md, plus run.json.
// Only wiring: every step is a stage-library function; this file decides order, options and files.
#pragma once

#include "filters/ExtractInterfaces.h"
#include "filters/SimplifyInterfaces.h"
#include "io/Case.h"
#include "io/Progress.h"
#include "levelset/CarveGaps.h"
#include "tet/Tetrahedralize.h"

#include <nlohmann/json.hpp>

#include <string>

namespace jawmesh {

struct RunOptions {
    double voxelSizeMm = 0.05;     ///< level-set voxel; the PDL needs >= 4 voxels across
    double bandVoxels = 3.0;       ///< narrow-band half width of the input level sets
    LoadOptions load;
    CarveOptions carve;
    ExtractOptions extract;
    SimplifyOptions simplify;
    TetOptions tet;
    bool writeLevelSets = false;   ///< also write <out>/<jaw>/levelsets/*.vdb
    std::string fromVdb;           ///< resume from a carved label field folder instead of surfaces
};

/// Default options for jaws (mesh sizes in mm chosen for the published jaw models' element counts).
RunOptions defaultRunOptions();

/// Reads a --config JSON file over `options` (keys as in runOptionsToJson); unknown keys are an
/// Error naming the file and key, so a typo never silently falls back to a default.
void applyRunConfig(const std::string& path, RunOptions& options);

/// The options as JSON, as recorded in run.json (and accepted by applyRunConfig).
nlohmann::json runOptionsToJson(const RunOptions& options);

/// Runs every stage for one jaw and writes <outJawDir>/{volumetric_meshes,surface_meshes,levelsets}
/// and <outJawDir>/run.json. The mesh is validated before anything of it is written; a violation is
/// an Error. Returns the run record written to run.json.
/// Throws Error for bad input or a failed stage, Cancelled when progress is cancelled.
nlohmann::json runJaw(const JawCase& jawCase, const RunOptions& options, const std::string& outJawDir,
                      Progress& progress = noProgress());

}  // namespace jawmesh
