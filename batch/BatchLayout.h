// Where a batch keeps things in its output folder (every path relative to <out>):
//   manifest.json                  the task list, options, options hash and every task's status
//   summary.csv                    the summary table as CSV
//   options.json                   the effective run options (a --config file every task reads)
//   <case>/<jaw>/                  the task's outputs, as `jawmesh run <case> -o <out>/<case>` writes
//                                  them, plus outputs.json (the completion stamp, batch/OutputStamp.h)
//   <case>/.<jaw>.partial-<host>-<pid>/   a task in flight (renamed to <case>/<jaw> when complete)
//   <case>/<jaw>.failed_surface/   the interface surface of a task whose TetGen step failed
//                                  (kept for study; removed when the task later succeeds)
//   tasks/<case>.<jaw>.json        a task's result record (written by the task itself)
//   logs/<case>.<jaw>.log          a local task's progress and errors
//   logs/slurm-<job>_<index>.log   a Slurm array task's output
//   slurm/batch.sbatch             the job-array script
#pragma once

#include "batch/Dataset.h"

#include <string>

namespace jawmesh {

std::string manifestPath(const std::string& outDir);
std::string summaryCsvPath(const std::string& outDir);
std::string optionsPath(const std::string& outDir);
std::string sbatchPath(const std::string& outDir);
std::string taskOutputDir(const std::string& outDir, const DatasetTask& task);
/// A fresh in-flight folder name for the task, unique per host and process.
std::string taskPartialDir(const std::string& outDir, const DatasetTask& task);
std::string taskResultPath(const std::string& outDir, const DatasetTask& task);
std::string taskFailedSurfaceDir(const std::string& outDir, const DatasetTask& task);
std::string taskLogPath(const std::string& outDir, const DatasetTask& task);
/// logs/<case>.<jaw>.log, relative to <out> (as recorded in the manifest).
std::string taskLogRelativePath(const DatasetTask& task);

/// Removes in-flight folders left by killed runs of this task (any host, any process).
/// Call only when no run of the task can be in flight.
void removeStalePartials(const std::string& outDir, const DatasetTask& task);

/// Replaces <case>/<jaw> by the completed partial folder: the old folder (if any) is moved aside,
/// the partial renamed into place, the old one removed. A kill in between leaves no folder or the
/// complete new one at <case>/<jaw>, never a mix. Throws Error when a rename fails.
void commitTaskOutput(const std::string& partialDir, const std::string& finalDir);

}  // namespace jawmesh
