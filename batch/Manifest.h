// The batch manifest, <out>/manifest.json: the dataset, the run options and their hash, and one
// record per task (case, jaw, status, seconds, peak memory, error). The coordinator (local batch,
// `--slurm` preparation, `--status`) is its only writer, always atomically (temp + rename), so a
// kill never leaves a torn manifest. Each task also writes its own result record
// (tasks/<case>.<jaw>.json, the same fields), which is how Slurm tasks report back.
#pragma once

#include "batch/Dataset.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace jawmesh {

enum class TaskStatus { Pending, Ok, Failed };

std::string statusName(TaskStatus status);  ///< "pending" | "ok" | "failed"

struct TaskRecord {
    DatasetTask task;
    TaskStatus status = TaskStatus::Pending;
    bool reused = false;                    ///< ok from an earlier run (outputs validated), not rerun
    double seconds = 0;                     ///< wall time of the run that made the outputs / failed
    std::uint64_t peakMemoryBytes = 0;      ///< peak resident memory of that run
    std::uint64_t estimatedMemoryBytes = 0; ///< batch/MemoryEstimate.h; 0 when unknown
    std::string error;                      ///< why it failed (one line), empty otherwise
    std::string log;                        ///< its log, relative to <out>
    std::string optionsHash;                ///< options the record is about (task result records)
};

struct BatchManifest {
    std::string datasetDir;          ///< absolute
    std::string jawmeshVersion;
    nlohmann::json options;          ///< runOptionsToJson of the batch's options
    std::string optionsHash;         ///< batch/OptionsHash.h
    std::string slurmJobId;          ///< set by --slurm --submit
    std::vector<TaskRecord> tasks;   ///< array task i is tasks[i]
};

nlohmann::json toJson(const TaskRecord& record);
/// Throws Error(source, reason) for a missing or mistyped field.
TaskRecord taskRecordFromJson(const nlohmann::json& j, const std::string& source);

nlohmann::json toJson(const BatchManifest& manifest);
BatchManifest manifestFromJson(const nlohmann::json& j, const std::string& source);

/// Writes <outDir>/manifest.json atomically. Throws Error on I/O failure.
void writeManifest(const BatchManifest& manifest, const std::string& outDir);
/// Reads <outDir>/manifest.json. Throws Error naming the file when it is missing or malformed.
BatchManifest readManifest(const std::string& outDir);

/// Writes the task's own result record atomically (tasks/<case>.<jaw>.json).
void writeTaskResult(const TaskRecord& record, const std::string& outDir);
/// The task's result record, or nothing when absent or unreadable (a task killed before writing it).
std::optional<TaskRecord> readTaskResult(const std::string& outDir, const DatasetTask& task);

}  // namespace jawmesh
