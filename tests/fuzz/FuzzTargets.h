// One entry per reader of user input, shared by the libFuzzer executables (fuzz_target.cpp, built
// by run_fuzzers.sh) and the normal tests, which replay the seed corpus and every input a fuzzer
// ever crashed on (tests/io/test_fuzz_inputs.cpp). The contract: a reader either returns a valid
// result or throws jawmesh::Error; any other exception escapes (a bug), and an invalid result makes
// the entry return false (a bug).
#pragma once

#include "cli/RunOptions.h"
#include "io/Error.h"
#include "io/MeshIO.h"
#include "io/ToothAxes.h"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace jawmesh::fuzz {

/// Every triangle indexes an existing vertex and every coordinate is finite.
inline bool validSurface(const SurfaceMesh& m) {
    if (m.triangles.empty()) return false;
    for (const Tri& t : m.triangles)
        for (std::int32_t v : t)
            if (v < 0 || static_cast<std::size_t>(v) >= m.vertices.size()) return false;
    for (const Vec3& v : m.vertices)
        if (!v.allFinite()) return false;
    return true;
}

inline bool readsSurface(const std::string& bytes, const std::string& name) {
    try {
        return validSurface(readSurfaceFromMemory(bytes, name));
    } catch (const Error&) {
        return true;
    }
}

/// Binary STL: the header's triangle count is made to agree with the size, so that the input
/// reaches the binary reader and the vertex welding instead of stopping at the size check.
inline bool stlBinary(const std::string& input) {
    std::string bytes = input;
    if (bytes.size() >= 84) {
        const std::uint32_t count = static_cast<std::uint32_t>((bytes.size() - 84) / 50);
        bytes.resize(84 + 50 * std::size_t(count));
        std::memcpy(bytes.data() + 80, &count, 4);
    }
    return readsSurface(bytes, "fuzz.stl");
}

/// ASCII STL: the input follows "solid", so it is read as text unless its size says binary.
inline bool stlAscii(const std::string& input) { return readsSurface("solid " + input, "fuzz.stl"); }
inline bool obj(const std::string& input) { return readsSurface(input, "fuzz.obj"); }
inline bool ply(const std::string& input) { return readsSurface(input, "fuzz.ply"); }
inline bool off(const std::string& input) { return readsSurface(input, "fuzz.off"); }

inline bool axesJson(const std::string& input) {
    try {
        for (const auto& [unn, a] : parseToothAxes(input, "fuzz.json")) {
            if (unn < 1 || unn > 32 || !a.crownCentre.allFinite()) return false;
            for (const Vec3* axis : {&a.mesialDistal, &a.labial, &a.occlusal})
                if (!axis->allFinite() || std::abs(axis->norm() - 1.0) > 1e-9) return false;
        }
    } catch (const Error&) {
    }
    return true;
}

inline bool configJson(const std::string& input) {
    RunOptions options = defaultRunOptions();
    try {
        applyRunConfigText(input, "fuzz.json", options);
    } catch (const Error&) {
        return true;
    }
    return options.voxelSizeMm > 0 && options.bandVoxels >= 1 && options.carve.pdlRatio >= 0 && options.carve.pdlRatio <= 1;
}

struct Target {
    const char* name;  ///< also the corpus folder: tests/fuzz/corpus/<name>/, regressions/<name>/
    bool (*run)(const std::string& input);
};

inline const std::vector<Target>& targets() {
    static const std::vector<Target> all = {{"stl_binary", stlBinary}, {"stl_ascii", stlAscii}, {"obj", obj},
                                            {"ply", ply},              {"off", off},            {"axes_json", axesJson},
                                            {"config_json", configJson}};
    return all;
}

}  // namespace jawmesh::fuzz
