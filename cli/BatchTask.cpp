// Implements cli/BatchTask.h; what it computes, its rules and its contract are documented there.
#include "cli/BatchTask.h"

#include "batch/BatchLayout.h"
#include "batch/Manifest.h"
#include "batch/OptionsHash.h"
#include "batch/OutputStamp.h"
#include "cli/Commands.h"
#include "cli/Pipeline.h"
#include "io/Error.h"
#include "io/ResourceUsage.h"

#include <cstdlib>
#include <filesystem>

namespace jawmesh {
namespace {

/// Slurm's own log for this array task when running under Slurm, else the local task log.
std::string taskLog(const DatasetTask& task) {
    const char* job = std::getenv("SLURM_ARRAY_JOB_ID");
    const char* index = std::getenv("SLURM_ARRAY_TASK_ID");
    if (job && index) return std::string("logs/slurm-") + job + "_" + index + ".log";
    return taskLogRelativePath(task);
}

const JawCase& findJaw(const CaseInfo& info, const DatasetTask& task) {
    for (const JawCase& jawCase : info.jaws)
        if (jawName(jawCase.jaw) == task.jaw) return jawCase;
    throw Error(task.caseDir, "has no " + task.jaw + " jaw any more (the dataset changed since the batch was planned)");
}

}  // namespace

void runBatchTask(const std::string& outDir, std::size_t index, Progress& progress) {
    const auto start = std::chrono::steady_clock::now();
    const BatchManifest manifest = readManifest(outDir);
    if (index >= manifest.tasks.size())
        throw Error(manifestPath(outDir), "has no task " + std::to_string(index) + " (it lists " +
                                              std::to_string(manifest.tasks.size()) + ")");
    RunOptions options = defaultRunOptions();
    applyRunConfig(optionsPath(outDir), options);
    const std::string hash = optionsHash(runOptionsToJson(options), JAWMESH_VERSION);
    if (hash != manifest.optionsHash)
        throw Error(optionsPath(outDir), "options hash " + hash + " differs from the manifest's " + manifest.optionsHash +
                                             " (was the batch planned with another jawmesh version?)");

    TaskRecord record = manifest.tasks[index];
    const DatasetTask& task = record.task;
    record.reused = false;
    record.optionsHash = hash;
    record.log = taskLog(task);
    const std::string partial = taskPartialDir(outDir, task);
    auto fail = [&](std::string message) {
        message = keepFailedSurface(partial, taskFailedSurfaceDir(outDir, task), message);
        std::error_code ec;
        std::filesystem::remove_all(partial, ec);
        record.status = TaskStatus::Failed;
        record.error = message;
        record.seconds = secondsSince(start);
        record.peakMemoryBytes = peakResidentMemoryBytes();
        writeTaskResult(record, outDir);
    };
    try {
        if (task.jaw.empty()) throw Error(task.discoveryError);
        removeStalePartials(outDir, task);
        runJaw(findJaw(discoverCase(task.caseDir), task), options, partial, progress);
        OutputStamp stamp;
        stamp.optionsHash = hash;
        stamp.seconds = secondsSince(start);
        stamp.peakMemoryBytes = peakResidentMemoryBytes();
        stamp.files = stampFiles(partial);
        writeOutputStamp(stamp, partial);
        commitTaskOutput(partial, taskOutputDir(outDir, task));
        std::error_code ec;
        std::filesystem::remove_all(taskFailedSurfaceDir(outDir, task), ec);  // an earlier failure's
        record.status = TaskStatus::Ok;
        record.error.clear();
        record.seconds = stamp.seconds;
        record.peakMemoryBytes = stamp.peakMemoryBytes;
        writeTaskResult(record, outDir);
    } catch (const Cancelled&) {
        std::error_code ec;
        std::filesystem::remove_all(partial, ec);
        throw;
    } catch (const Error& e) {
        fail(e.what());
        throw;
    } catch (const std::bad_alloc&) {
        fail("out of memory (try a larger voxel_mm in the config, or give the task more memory)");
        throw;
    } catch (const std::exception& e) {
        fail(std::string("internal error: ") + e.what());
        throw;
    }
}

}  // namespace jawmesh
