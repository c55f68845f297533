// Implements batch/Manifest.h; what it computes, its rules and its contract are documented there.
#include "batch/Manifest.h"

#include "batch/BatchLayout.h"
#include "io/AtomicFile.h"
#include "io/Error.h"

#include <fstream>

namespace jawmesh {

std::string statusName(TaskStatus status) {
    switch (status) {
        case TaskStatus::Ok: return "ok";
        case TaskStatus::Failed: return "failed";
        case TaskStatus::Pending: break;
    }
    return "pending";
}

namespace {
TaskStatus statusFromName(const std::string& name, const std::string& source) {
    for (TaskStatus s : {TaskStatus::Pending, TaskStatus::Ok, TaskStatus::Failed})
        if (statusName(s) == name) return s;
    throw Error(source, "unknown task status '" + name + "'");
}

nlohmann::json readJsonFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path, "cannot open (is this a batch output folder?)");
    try {
        return nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, std::string("invalid JSON: ") + e.what());
    }
}
}  // namespace

nlohmann::json toJson(const TaskRecord& r) {
    return {{"case", r.task.caseName},
            {"case_dir", r.task.caseDir},
            {"jaw", r.task.jaw},
            {"discovery_error", r.task.discoveryError},
            {"status", statusName(r.status)},
            {"reused", r.reused},
            {"seconds", r.seconds},
            {"peak_memory_bytes", r.peakMemoryBytes},
            {"estimated_memory_bytes", r.estimatedMemoryBytes},
            {"error", r.error},
            {"log", r.log},
            {"options_hash", r.optionsHash}};
}

TaskRecord taskRecordFromJson(const nlohmann::json& j, const std::string& source) {
    TaskRecord r;
    try {
        r.task.caseName = j.at("case").get<std::string>();
        r.task.caseDir = j.at("case_dir").get<std::string>();
        r.task.jaw = j.at("jaw").get<std::string>();
        r.task.discoveryError = j.at("discovery_error").get<std::string>();
        r.status = statusFromName(j.at("status").get<std::string>(), source);
        r.reused = j.at("reused").get<bool>();
        r.seconds = j.at("seconds").get<double>();
        r.peakMemoryBytes = j.at("peak_memory_bytes").get<std::uint64_t>();
        r.estimatedMemoryBytes = j.at("estimated_memory_bytes").get<std::uint64_t>();
        r.error = j.at("error").get<std::string>();
        r.log = j.at("log").get<std::string>();
        r.optionsHash = j.at("options_hash").get<std::string>();
    } catch (const nlohmann::json::exception& e) {
        throw Error(source, std::string("malformed task record: ") + e.what());
    }
    return r;
}

nlohmann::json toJson(const BatchManifest& m) {
    nlohmann::json tasks = nlohmann::json::array();
    for (const TaskRecord& r : m.tasks) tasks.push_back(toJson(r));
    return {{"dataset", m.datasetDir},     {"jawmesh_version", m.jawmeshVersion},
            {"options", m.options},        {"options_hash", m.optionsHash},
            {"slurm_job_id", m.slurmJobId}, {"tasks", tasks}};
}

BatchManifest manifestFromJson(const nlohmann::json& j, const std::string& source) {
    BatchManifest m;
    try {
        m.datasetDir = j.at("dataset").get<std::string>();
        m.jawmeshVersion = j.at("jawmesh_version").get<std::string>();
        m.options = j.at("options");
        m.optionsHash = j.at("options_hash").get<std::string>();
        m.slurmJobId = j.at("slurm_job_id").get<std::string>();
        for (const nlohmann::json& t : j.at("tasks")) m.tasks.push_back(taskRecordFromJson(t, source));
    } catch (const nlohmann::json::exception& e) {
        throw Error(source, std::string("malformed manifest: ") + e.what());
    }
    return m;
}

void writeManifest(const BatchManifest& manifest, const std::string& outDir) {
    writeFileAtomically(manifestPath(outDir), [&](std::ostream& out) { out << toJson(manifest).dump(2) << '\n'; },
                        false);
}

BatchManifest readManifest(const std::string& outDir) {
    const std::string path = manifestPath(outDir);
    return manifestFromJson(readJsonFile(path), path);
}

void writeTaskResult(const TaskRecord& record, const std::string& outDir) {
    writeFileAtomically(taskResultPath(outDir, record.task),
                        [&](std::ostream& out) { out << toJson(record).dump(2) << '\n'; }, false);
}

std::optional<TaskRecord> readTaskResult(const std::string& outDir, const DatasetTask& task) {
    const std::string path = taskResultPath(outDir, task);
    try {
        return taskRecordFromJson(readJsonFile(path), path);
    } catch (const Error&) {
        return std::nullopt;
    }
}

}  // namespace jawmesh
