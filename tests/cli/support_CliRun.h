// Running the jawmesh binary from tests: exit code and what it printed, and the checks every
// refused or interrupted run must pass (nothing written, no staging or temporary leftovers).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace jawmesh::test {

struct CliResult {
    int exitCode = -1;   ///< -1 when killed by a signal
    std::string output;  ///< stdout and stderr
};

/// Runs `<jawmesh> <args>` through the shell, output captured in logPath.
CliResult runJawmesh(const std::string& args, const std::filesystem::path& logPath);

/// Regular files under dir (recursively, hidden ones included), relative to dir; empty when dir
/// does not exist. Sorted.
std::vector<std::string> filesUnder(const std::filesystem::path& dir);

/// Entries under dir whose names mark an unfinished write: "*.partial-*" staging folders and
/// "*.tmp-*" temporary files.
std::vector<std::string> leftoversUnder(const std::filesystem::path& dir);

/// tests/batch/fast_phantom.json: voxel 0.2 mm and coarse tets, a phantom run in seconds.
std::string fastConfig();

}  // namespace jawmesh::test
