// Implements batch/Dataset.h; what it computes, its rules and its contract are documented there.
#include "batch/Dataset.h"

#include "io/Case.h"
#include "io/Error.h"

#include <algorithm>
#include <filesystem>

namespace jawmesh {
namespace fs = std::filesystem;

std::vector<DatasetTask> discoverDataset(const std::string& datasetDir, const std::string& excludeDir) {
    std::error_code ec;
    if (!fs::is_directory(datasetDir, ec)) throw Error(datasetDir, "dataset folder does not exist");
    const fs::path root = fs::absolute(datasetDir).lexically_normal();
    if (fs::is_directory(root / "input", ec))
        throw Error(datasetDir, "is a case folder, not a dataset of cases: use `jawmesh run`, or give its parent folder");
    std::vector<fs::path> cases;
    for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_directory() && it->path().filename().string().rfind('.', 0) != 0 &&
            (excludeDir.empty() || it->path() != fs::absolute(excludeDir).lexically_normal()))
            cases.push_back(it->path());
    if (ec) throw Error(datasetDir, "cannot list folder: " + ec.message());
    if (cases.empty()) throw Error(datasetDir, "no case folder (expected <dataset>/<case>/input/<jaw>/...)");
    std::sort(cases.begin(), cases.end());

    std::vector<DatasetTask> tasks;
    for (const fs::path& dir : cases) {
        DatasetTask base;
        base.caseName = dir.filename().string();
        base.caseDir = dir.string();
        try {
            for (const JawCase& jaw : discoverCase(base.caseDir).jaws) {
                DatasetTask task = base;
                task.jaw = jawName(jaw.jaw);
                tasks.push_back(task);
            }
        } catch (const Error& e) {
            base.discoveryError = e.what();
            tasks.push_back(base);
        }
    }
    return tasks;
}

std::string taskName(const DatasetTask& task) {
    return task.jaw.empty() ? task.caseName : task.caseName + "/" + task.jaw;
}

}  // namespace jawmesh
