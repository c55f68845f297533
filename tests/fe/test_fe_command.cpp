// `jawmesh fe` end to end on a jaw folder laid out like a run's output: decks written, CalculiX
// solved, summary JSON with every crown moving lingually.
#include "fe/FeTestMeshes.h"
#include "io/GmshWriter.h"
#include "support/TestData.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace jawmesh {
namespace {

TEST(FeCommand, WritesDecksSolvesWithCalculixAndSummarises) {
    const auto out = test::scratchDir("fe-command");
    const auto jawDir = out / "mandible";
    writeGmsh(test::gridJawBlock(), (jawDir / "volumetric_meshes" / "mandible.msh").string());
    const std::string cmd = std::string(JAWMESH_BINARY) + " --quiet fe " + jawDir.string() +
                            " --scenario tipping --format feb,polyfem,inp --order 1 --solve > " + (out / "stdout.json").string();
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    for (const char* f : {"tipping.inp", "tipping.feb", "tipping_polyfem.json", "tipping_polyfem.msh", "tipping_axes.json",
                          "tipping_calculix_summary.json", "tipping.frd", "tipping.dat"})
        EXPECT_TRUE(std::filesystem::exists(jawDir / "simulation" / f)) << f;
    std::ifstream in(jawDir / "simulation" / "tipping_calculix_summary.json");
    const auto summary = nlohmann::json::parse(in);
    EXPECT_EQ(summary.at("status"), "completed");
    ASSERT_EQ(summary.at("teeth").size(), 2u);
    for (const auto& t : summary.at("teeth")) EXPECT_GT(t.at("along_force_mm").get<double>(), 0.0);
    EXPECT_GT(summary.at("regions").at("pdl_24").at("max_von_mises_mpa").get<double>(), 0.0);

    // A bad jaw folder is one clear error and a non-zero exit code.
    const std::string bad = std::string(JAWMESH_BINARY) + " --quiet fe " + out.string() + " 2> " + (out / "err.txt").string();
    EXPECT_NE(std::system(bad.c_str()), 0);
}

}  // namespace
}  // namespace jawmesh
