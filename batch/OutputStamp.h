// The completion stamp of one task's output folder, <out>/<case>/<jaw>/outputs.json: the options
// hash the outputs were made with and every file's size and checksum. It is written last, inside
// the temporary folder, before that folder is renamed into place; so a folder with a valid stamp
// is complete, and a rerun can tell finished work (skip) from partial, stale or damaged work (redo).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace jawmesh {

struct StampedFile {
    std::string path;      ///< relative to the output folder, '/'-separated
    std::uint64_t bytes = 0;
    std::string checksum;  ///< fileChecksumHex
};

struct OutputStamp {
    std::string optionsHash;
    double seconds = 0;                ///< wall time of the run that made the outputs
    std::uint64_t peakMemoryBytes = 0; ///< its peak resident memory
    std::vector<StampedFile> files;    ///< sorted by path; the stamp itself is not listed
};

/// The stamp file's name inside an output folder.
inline constexpr const char* kOutputStampName = "outputs.json";

/// Lists every regular file under dir (recursively, except the stamp) with size and checksum.
/// Throws Error naming a file that cannot be read. Cost: reads every byte once.
std::vector<StampedFile> stampFiles(const std::string& dir);

/// Writes <dir>/outputs.json atomically. Throws Error on I/O failure.
void writeOutputStamp(const OutputStamp& stamp, const std::string& dir);

/// Why dir does not hold complete outputs for optionsHash, or "" when it does: the stamp exists and
/// parses, its hash is optionsHash, each of `required` (relative paths) is listed, and every listed
/// file exists with its recorded size and checksum. On success *stamp (if given) receives the stamp.
/// Never throws for a damaged folder (that is a reason, not an error).
std::string outputProblem(const std::string& dir, const std::string& optionsHash,
                          const std::vector<std::string>& required, OutputStamp* stamp = nullptr);

}  // namespace jawmesh
