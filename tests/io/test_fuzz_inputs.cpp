// Replays every fuzzer seed (tests/fuzz/corpus/<target>/) and every input a fuzzer once failed on
// (tests/fuzz/regressions/<target>/) through the same entries the fuzzers call
// (tests/fuzz/FuzzTargets.h): each must be read or refused with jawmesh::Error, never crash, throw
// anything else or give an invalid result. Runs in the normal (and sanitizer) test sets.
#include "cli/RunOptions.h"
#include "fuzz/FuzzTargets.h"
#include "io/MeshIO.h"
#include "io/ToothAxes.h"
#include "io/IoTestUtil.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace jawmesh::test {
namespace {
namespace fs = std::filesystem;

std::vector<fs::path> filesIn(const fs::path& dir) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        if (it->is_regular_file() && it->path().filename().string()[0] != '.') files.push_back(it->path());
    std::sort(files.begin(), files.end());
    return files;
}

TEST(FuzzInputs, SeedsAndRegressionsAreReadOrRefusedCleanly) {
    const fs::path root = fs::path(JAWMESH_SOURCE_DIR) / "tests" / "fuzz";
    for (const fuzz::Target& t : fuzz::targets()) {
        const std::vector<fs::path> seeds = filesIn(root / "corpus" / t.name);
        EXPECT_FALSE(seeds.empty()) << "no seed corpus for fuzz target " << t.name;
        std::vector<fs::path> inputs = seeds;
        for (const fs::path& p : filesIn(root / "regressions" / t.name)) inputs.push_back(p);
        for (const fs::path& p : inputs) {
            SCOPED_TRACE(p.string());
            EXPECT_TRUE(t.run(readBytes(p)));
        }
    }
}

/// The seeds must reach the readers' deep paths (welding, lists, relative indices), not stop at a
/// header check: each surface target has a seed that reads as a tetrahedron or a quad.
TEST(FuzzInputs, SurfaceSeedsAreValidFiles) {
    const fs::path corpus = fs::path(JAWMESH_SOURCE_DIR) / "tests" / "fuzz" / "corpus";
    const std::vector<std::pair<std::string, std::string>> seeds = {
        {"stl_binary/tetra.stl", "x.stl"}, {"obj/tetra.obj", "x.obj"}, {"obj/quad.obj", "x.obj"},
        {"ply/tetra_ascii.ply", "x.ply"},  {"ply/tetra_binary.ply", "x.ply"}, {"off/tetra.off", "x.off"},
        {"off/coff_quad.off", "x.off"}};
    for (const auto& [file, name] : seeds) {
        SCOPED_TRACE(file);
        const SurfaceMesh m = readSurfaceFromMemory(readBytes(corpus / file), name);
        EXPECT_TRUE(m.triangles.size() == 4 || m.triangles.size() == 2) << m.triangles.size();
        EXPECT_EQ(m.vertices.size(), 4u);
    }
    const SurfaceMesh ascii = readSurfaceFromMemory("solid " + readBytes(corpus / "stl_ascii/tetra.stl"), "x.stl");
    EXPECT_EQ(ascii.triangles.size(), 4u);
    EXPECT_EQ(parseToothAxes(readBytes(corpus / "axes_json/two_teeth.json"), "x.json").size(), 2u);
    RunOptions options = defaultRunOptions();
    applyRunConfigText(readBytes(corpus / "config_json/profile.json"), "x.json", options);
    EXPECT_TRUE(options.carve.profile.has_value());
}

}  // namespace
}  // namespace jawmesh::test
