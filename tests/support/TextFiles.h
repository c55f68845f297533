// Whole files as text, for the tests: one reader and one writer instead of one per test file.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace jawmesh::test {

/// The file's bytes; empty when it cannot be read.
inline std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Writes `text` as the whole file, making its folder first.
inline void writeText(const std::filesystem::path& path, const std::string& text) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

/// The file parsed as JSON (throws nlohmann's parse error for a missing or malformed file).
inline nlohmann::json readJson(const std::filesystem::path& path) { return nlohmann::json::parse(readText(path)); }

}  // namespace jawmesh::test
