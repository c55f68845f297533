// A batch on this machine: every pending task of the manifest runs as a child process
// (`jawmesh --threads T batch --array-task <i> -o <out>`, the same entry point a Slurm array task
// uses), several at once when their memory estimates fit the budget (batch/Schedule.h).
#pragma once

#include "batch/Manifest.h"

#include <cstdint>
#include <functional>
#include <string>

namespace jawmesh {

struct LocalBatchOptions {
    std::string jawmeshPath;               ///< the executable to start (absolute)
    int maxJobs = 1;                       ///< tasks at once, at most
    int threadsPerTask = 1;                ///< each task's --threads
    std::uint64_t memoryBudgetBytes = 0;   ///< sum of the running tasks' estimates stays below this
    std::function<bool()> cancelled;       ///< polled; when true, running tasks get SIGINT, none starts
    /// Called after each task ends (record updated, manifest written); for progress lines.
    std::function<void(const TaskRecord& record)> taskFinished;
    /// Called when a task starts alone because its estimate exceeds the budget.
    std::function<void(const std::string& warning)> warn;
};

/// Runs every Pending task; updates its record (Ok, or Failed with the task's error, or for a
/// crashed task "crashed: killed by signal N (...)" and its log) with the measured wall time and
/// peak memory (wait4 of the child), and rewrites <outDir>/manifest.json after each task ends.
/// Tasks interrupted by `cancelled` stay Pending. The caller holds the output folder's FolderLock.
/// Throws Error when a task process cannot be started.
void runLocalBatch(BatchManifest& manifest, const std::string& outDir, const LocalBatchOptions& options);

}  // namespace jawmesh
