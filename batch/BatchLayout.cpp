// Implements batch/BatchLayout.h; what it computes, its rules and its contract are documented there.
#include "batch/BatchLayout.h"

#include "io/Error.h"
#include "io/StagedFolder.h"

#include <filesystem>
#include <unistd.h>

namespace jawmesh {
namespace fs = std::filesystem;

namespace {
std::string fileStem(const DatasetTask& task) { return task.jaw.empty() ? task.caseName : task.caseName + "." + task.jaw; }

std::string hostName() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0) return "host";
    return name;
}

std::string partialPrefix(const DatasetTask& task) { return "." + task.jaw + ".partial-"; }
}  // namespace

std::string manifestPath(const std::string& outDir) { return outDir + "/manifest.json"; }
std::string summaryCsvPath(const std::string& outDir) { return outDir + "/summary.csv"; }
std::string optionsPath(const std::string& outDir) { return outDir + "/options.json"; }
std::string sbatchPath(const std::string& outDir) { return outDir + "/slurm/batch.sbatch"; }

std::string taskOutputDir(const std::string& outDir, const DatasetTask& task) {
    return outDir + "/" + task.caseName + "/" + task.jaw;
}

std::string taskPartialDir(const std::string& outDir, const DatasetTask& task) {
    return outDir + "/" + task.caseName + "/" + partialPrefix(task) + hostName() + "-" +
           std::to_string(static_cast<long>(::getpid()));
}

std::string taskFailedSurfaceDir(const std::string& outDir, const DatasetTask& task) {
    return outDir + "/" + task.caseName + "/" + task.jaw + ".failed_surface";
}

std::string taskResultPath(const std::string& outDir, const DatasetTask& task) {
    return outDir + "/tasks/" + fileStem(task) + ".json";
}

std::string taskLogRelativePath(const DatasetTask& task) { return "logs/" + fileStem(task) + ".log"; }

std::string taskLogPath(const std::string& outDir, const DatasetTask& task) {
    return outDir + "/" + taskLogRelativePath(task);
}

void removeStalePartials(const std::string& outDir, const DatasetTask& task) {
    const fs::path caseOut = fs::path(outDir) / task.caseName;
    std::error_code ec;
    if (task.jaw.empty() || !fs::is_directory(caseOut, ec)) return;
    const std::string prefix = partialPrefix(task);
    std::vector<fs::path> stale;
    for (fs::directory_iterator it(caseOut, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename().string().rfind(prefix, 0) == 0) stale.push_back(it->path());
    for (const fs::path& p : stale) fs::remove_all(p, ec);
}

void commitTaskOutput(const std::string& partialDir, const std::string& finalDir) { replaceFolder(partialDir, finalDir); }

}  // namespace jawmesh
