// Implements the test helpers of support_CliRun.h (documented there).
#include "support_CliRun.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sys/wait.h>

namespace jawmesh::test {
namespace fs = std::filesystem;

CliResult runJawmesh(const std::string& args, const fs::path& logPath) {
    fs::create_directories(logPath.parent_path());
    const std::string command = std::string(JAWMESH_BINARY) + " " + args + " > " + logPath.string() + " 2>&1";
    const int status = std::system(command.c_str());
    CliResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(logPath);
    r.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return r;
}

std::vector<std::string> filesUnder(const fs::path& dir) {
    std::vector<std::string> files;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return files;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (!e.is_directory()) files.push_back(e.path().lexically_relative(dir).string());
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<std::string> leftoversUnder(const fs::path& dir) {
    std::vector<std::string> found;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return found;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        const std::string name = e.path().filename().string();
        if (name.find(".partial-") != std::string::npos || name.find(".tmp-") != std::string::npos)
            found.push_back(e.path().lexically_relative(dir).string());
    }
    return found;
}

std::string fastConfig() { return std::string(JAWMESH_SOURCE_DIR) + "/tests/batch/fast_phantom.json"; }

}  // namespace jawmesh::test
