// The options of a whole run (`jawmesh run`, `batch`): defaults, the --config JSON file over them,
// and the JSON recorded in run.json (the same keys), so a run can be repeated from its record.
#pragma once

#include "filters/ExtractInterfaces.h"
#include "filters/SimplifyInterfaces.h"
#include "io/Case.h"
#include "io/Edits.h"
#include "levelset/CarveGaps.h"
#include "tet/Tetrahedralize.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>

namespace jawmesh {

struct RunOptions {
    double voxelSizeMm = 0.05;     ///< level-set voxel; the PDL needs >= 4 voxels across
    double bandVoxels = 3.0;       ///< narrow-band half width of the input level sets
    /// The bone's band half width away from the teeth (levelset/JawLevelSets.h): carving reads
    /// the bone's distance beyond its surface only around the teeth, and the band's cost grows
    /// with its width (2 instead of 3 voxels there: the shared mandible's level sets about 1 s
    /// faster, the same mesh).
    double boneFarBandVoxels = 2.0;
    LoadOptions load;
    CarveOptions carve;
    ExtractOptions extract;
    SimplifyOptions simplify;
    TetOptions tet;
    bool writeLevelSets = false;   ///< also write <out>/<jaw>/levelsets/*.vdb
    std::string fromVdb;           ///< resume from a carved label field folder instead of surfaces
    EditList edits;                ///< what-ifs applied before carving (levelset/JawEdits.h); none when empty
    /// Refuse the jaw up front when its memory estimate (batch/MemoryEstimate.h) exceeds this many
    /// bytes; 0: no check. Where the run happens, not what it computes: not in runOptionsToJson.
    std::uint64_t memoryLimitBytes = 0;
};

/// The surface bounds for a jaw whose input is a label map of voxels labelVoxelMm across (0 for
/// surfaces): the bone's at most kLabelVoxelBoundShare of a voxel, so that the mesh stays within a
/// voxel of the labels (issue #23; the defaults, 0.08 mm near the teeth and 0.15 farther, left the
/// 0.1 mm phantom's bone 0.155 mm from its label surface). Tooth and PDL bounds are tighter already.
SimplifyOptions simplifyOptionsFor(SimplifyOptions options, double labelVoxelMm);
constexpr double kLabelVoxelBoundShare = 0.8;

/// Default options for jaws (mesh sizes in mm chosen for the published jaw models' element counts).
RunOptions defaultRunOptions();

/// Reads a --config JSON file over `options` (keys as in runOptionsToJson); unknown keys are an
/// Error naming the file and key, so a typo never silently falls back to a default; so are wrong
/// types and values out of range.
void applyRunConfig(const std::string& path, RunOptions& options);

/// The options as JSON, as recorded in run.json (and accepted by applyRunConfig).
nlohmann::json runOptionsToJson(const RunOptions& options);

/// applyRunConfig on JSON text held in memory; `name` names it in messages (what the fuzzer and
/// applyRunConfig use). Throws Error(name, reason) for invalid JSON, unknown keys, wrong value
/// types and out-of-range values (e.g. a voxel of 0 mm, a PDL ratio above 1).
void applyRunConfigText(const std::string& text, const std::string& name, RunOptions& options);

}  // namespace jawmesh
