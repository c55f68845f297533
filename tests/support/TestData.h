// Paths for tests: the shared real anatomy (read-only, beside the checkout) and a scratch folder.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

namespace jawmesh::test {

/// ../shared/data/<relative>; the test is skipped (not passed) when the shared data is absent.
inline std::string sharedData(const std::string& relative) {
    return std::string(JAWMESH_SHARED_DATA) + "/" + relative;
}

#define JAWMESH_REQUIRE_SHARED(path)                                                   \
    do {                                                                              \
        if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data missing: " << (path); \
    } while (0)

/// A fresh empty folder under the build tree for this test's files.
inline std::filesystem::path scratchDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("jawmesh-test-" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// scratchDir(name) made unique to this process: for folders a fixture sets up once and shares
/// between its tests. ctest runs every test as its own process, in parallel, so a shared name
/// would let one process wipe the folder another is still using.
inline std::filesystem::path processScratchDir(const std::string& name) {
    return scratchDir(name + "-" + std::to_string(::getpid()));
}

}  // namespace jawmesh::test
