// `jawmesh fe` end to end on jaw folders laid out like a run's output: decks written, CalculiX
// solved, summary JSON with every crown moving lingually; biting across the two jaws' folders.
#include "fe/FeTestMeshes.h"
#include "io/GmshWriter.h"
#include "support/TestData.h"
#include "tet/GridTetMesh.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

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

/// The jaws of the two-crown bite (tests/fe/test_calculix.cpp) as two meshes, as `jawmesh run`
/// writes them: the mandible with tooth 24 up to z = 6, the maxilla with tooth 9 from z = 6.5.
TetMesh biteHalf(Jaw jaw) {
    return test::withoutOutside(test::gridTetMesh(8, 4, 28, 0.5, [jaw](const Vec3& p) -> Label {
        const bool crownColumn = p.x() > 1 && p.x() < 3 && p.y() > 0.5 && p.y() < 1.5;
        if (jaw == Jaw::Mandible) return p.z() < 5 ? kMandibleBoneLabel : crownColumn && p.z() < 6.1 ? toothLabel(24) : kOutsideLabel;
        return p.z() > 8 ? kMaxillaBoneLabel : crownColumn && p.z() > 6.6 ? toothLabel(9) : kOutsideLabel;
    }));
}

TEST(FeCommand, BitingTakesTheOtherJawFromTheSiblingFolderAndSolvesWithContact) {
    const auto out = test::scratchDir("fe-command-biting");
    writeGmsh(biteHalf(Jaw::Mandible), (out / "mandible" / "volumetric_meshes" / "mandible.msh").string());
    // Without the maxilla: one clear error naming what is missing.
    const std::string alone = std::string(JAWMESH_BINARY) + " --quiet fe " + (out / "mandible").string() +
                              " --scenario biting 2> " + (out / "err.txt").string();
    EXPECT_NE(std::system(alone.c_str()), 0);
    std::ifstream err(out / "err.txt");
    const std::string message((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
    EXPECT_NE(message.find("maxilla"), std::string::npos) << message;

    writeGmsh(biteHalf(Jaw::Maxilla), (out / "maxilla" / "volumetric_meshes" / "maxilla.msh").string());
    const std::string cmd = std::string(JAWMESH_BINARY) + " --quiet fe " + (out / "mandible").string() +
                            " --scenario biting --format feb,polyfem,inp --solve > " + (out / "stdout.json").string();
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    for (const char* f : {"biting.inp", "biting.feb", "biting_polyfem.json", "biting_polyfem.msh", "biting_calculix_summary.json"})
        EXPECT_TRUE(std::filesystem::exists(out / "mandible" / "simulation" / f)) << f;
    std::ifstream in(out / "mandible" / "simulation" / "biting_calculix_summary.json");
    const auto summary = nlohmann::json::parse(in);
    EXPECT_EQ(summary.at("status"), "completed");
    // Both jaws' regions were solved, and stress reached the maxilla through the crowns' contact.
    for (const char* region : {"bone_mandible", "bone_maxilla", "tooth_24", "tooth_9"})
        EXPECT_GT(summary.at("regions").at(region).at("max_von_mises_mpa").get<double>(), 0.0) << region;
}

}  // namespace
}  // namespace jawmesh
