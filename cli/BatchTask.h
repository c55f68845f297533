// One task of a batch, in this process: what `jawmesh batch --array-task <i> -o <out>` runs, both
// as a local batch's child process and as a Slurm array task.
#pragma once

#include "io/Progress.h"

#include <cstddef>
#include <string>

namespace jawmesh {

/// Runs task `index` of <outDir>/manifest.json with the options of <outDir>/options.json: the jaw's
/// pipeline (runJaw) into a fresh partial folder, the completion stamp written last, then the folder
/// renamed to <out>/<case>/<jaw>. Writes the task's result record (tasks/<case>.<jaw>.json) in every
/// outcome but a kill. Throws Error for a bad manifest, options whose hash differs from the
/// manifest's (another jawmesh version), and for the task's own failure (after recording it);
/// Cancelled when progress is cancelled (partial folder removed, nothing recorded).
void runBatchTask(const std::string& outDir, std::size_t index, Progress& progress);

}  // namespace jawmesh
