// One entry per reader of user input, shared by the libFuzzer executables (fuzz_target.cpp, built
// by run_fuzzers.sh) and the normal tests, which replay the seed corpus and every input a fuzzer
// ever failed on (tests/io/test_fuzz_inputs.cpp). The contract: a reader either returns a valid
// result or throws jawmesh::Error; any other exception escapes (a bug), and an invalid result makes
// the entry return false (a bug).
#pragma once

#include <string>
#include <vector>

namespace jawmesh::fuzz {

/// Binary STL: the header's triangle count is made to agree with the size, so that the input
/// reaches the binary reader and the vertex welding instead of stopping at the size check.
bool stlBinary(const std::string& input);
/// ASCII STL: the input follows "solid", so it is read as text unless its size says binary.
bool stlAscii(const std::string& input);
bool obj(const std::string& input);
bool ply(const std::string& input);
bool off(const std::string& input);
/// Tooth axes JSON (io/ToothAxes.h): valid UNNs, finite centres, finite unit axes.
bool axesJson(const std::string& input);
/// Run config JSON (cli/RunOptions.h): accepted options are within their ranges.
bool configJson(const std::string& input);
/// Edit files (io/Edits.h), from a temporary file: every edit read names valid UNNs and has
/// positive, finite lengths.
bool editsJson(const std::string& input);
/// Label volumes (io/LabelVolume.h), from a temporary file (the libraries read files): a volume
/// read has as many values as voxels, a finite non-degenerate map and a labelled voxel.
bool nrrd(const std::string& input);
bool nifti(const std::string& input);
/// labels.json (io/LabelRoles.h) for a fixed small volume: every segment gets a role.
bool labelsJson(const std::string& input);

struct Target {
    const char* name;  ///< also the corpus folder: tests/fuzz/corpus/<name>/, regressions/<name>/
    bool (*run)(const std::string& input);
};

/// Every target above, by name.
const std::vector<Target>& targets();

}  // namespace jawmesh::fuzz
