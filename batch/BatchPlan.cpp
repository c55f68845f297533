// Implements batch/BatchPlan.h; what it computes, its rules and its contract are documented there.
#include "batch/BatchPlan.h"

#include "batch/BatchLayout.h"
#include "batch/MemoryEstimate.h"
#include "batch/OutputStamp.h"
#include "io/Case.h"
#include "io/Error.h"
#include "levelset/JawInput.h"

#include <algorithm>

namespace jawmesh {
namespace {

/// 0 when the jaw cannot be read: its task will fail with the reader's message.
std::uint64_t estimateTaskMemory(const DatasetTask& task, double voxelMm) {
    try {
        for (const JawCase& jawCase : discoverCase(task.caseDir).jaws) {
            if (jawName(jawCase.jaw) != task.jaw) continue;
            return estimateJawMemoryBytes(loadJawInput(jawCase), voxelMm);
        }
    } catch (const Error&) {
    }
    return 0;
}

}  // namespace

std::vector<std::string> requiredOutputs(const std::string& jaw) {
    return {"run.json", "volumetric_meshes/" + jaw + ".msh", "volumetric_meshes/" + jaw + ".vtu",
            "volumetric_meshes/labels.json"};
}

BatchManifest planBatch(const std::string& datasetDir, const std::string& outDir, const nlohmann::json& options,
                        const std::string& optionsHash, const std::string& jawmeshVersion) {
    BatchManifest m;
    m.datasetDir = datasetDir;
    m.jawmeshVersion = jawmeshVersion;
    m.options = options;
    m.optionsHash = optionsHash;
    const double voxelMm = options.at("voxel_mm").get<double>();
    for (const DatasetTask& task : discoverDataset(datasetDir, outDir)) {
        TaskRecord r;
        r.task = task;
        r.optionsHash = optionsHash;
        r.log = taskLogRelativePath(task);
        OutputStamp stamp;
        if (task.jaw.empty()) {
            r.status = TaskStatus::Failed;
            r.error = task.discoveryError;
        } else if (outputProblem(taskOutputDir(outDir, task), optionsHash, requiredOutputs(task.jaw), &stamp).empty()) {
            r.status = TaskStatus::Ok;
            r.reused = true;
            r.seconds = stamp.seconds;
            r.peakMemoryBytes = stamp.peakMemoryBytes;
        } else {
            r.estimatedMemoryBytes = estimateTaskMemory(task, voxelMm);
        }
        m.tasks.push_back(r);
    }
    return m;
}

TaskRecord collectTaskStatus(const TaskRecord& planned, const std::string& outDir, const std::string& optionsHash,
                             const std::string& missing) {
    if (planned.task.jaw.empty()) return planned;
    TaskRecord r = planned;
    r.error.clear();
    OutputStamp stamp;
    const std::string problem =
        outputProblem(taskOutputDir(outDir, r.task), optionsHash, requiredOutputs(r.task.jaw), &stamp);
    const std::optional<TaskRecord> result = readTaskResult(outDir, r.task);
    const bool resultApplies = result && result->optionsHash == optionsHash;
    if (problem.empty()) {
        r.status = TaskStatus::Ok;
        r.seconds = stamp.seconds;
        r.peakMemoryBytes = stamp.peakMemoryBytes;
        if (resultApplies && !result->log.empty()) r.log = result->log;
        return r;
    }
    r.reused = false;
    if (resultApplies) {
        r.status = TaskStatus::Failed;
        r.seconds = result->seconds;
        r.peakMemoryBytes = result->peakMemoryBytes;
        if (!result->log.empty()) r.log = result->log;
        r.error = result->status == TaskStatus::Failed ? result->error : "outputs damaged after completion: " + problem;
        return r;
    }
    r.status = TaskStatus::Pending;
    r.error = missing;
    return r;
}

}  // namespace jawmesh
