// `jawmesh run --edits` (issue #24) on the 2-tooth phantom at 0.1 mm voxels (seconds per run): the
// what-ifs reach the mesh (no label of an extracted tooth, the socket's volume turned into bone,
// the edited PDL's thickness), run.json and the report record them, and a wrong edit is refused
// before any work with the file and the entry named.
#include "io/GmshReader.h"
#include "io/Labels.h"
#include "support/TestData.h"
#include "support_CliRun.h"
#include "support_RunChecks.h"
#include "tet/ElementQuality.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

/// Writes the edits, runs the phantom case with them into <dir>/<name>, returns the jaw folder.
fs::path runWithEdits(const fs::path& dir, const std::string& name, const nlohmann::json& edits) {
    const fs::path file = dir / (name + ".json");
    std::ofstream(file) << nlohmann::json{{"edits", edits}}.dump();
    const test::CliResult r = test::runJawmesh("-q run " + (dir / "case").string() + " -o " + (dir / name).string() +
                                                   " --voxel 0.1 --edits " + file.string(),
                                               dir / (name + ".log"));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return dir / name / "mandible";
}

TEST(RunEdits, WhatIfsReachTheMeshRunJsonAndReport) {
    const fs::path dir = test::scratchDir("run-edits");
    ASSERT_EQ(test::runJawmesh("-q phantom " + (dir / "case").string() + " --teeth 2", dir / "phantom.log").exitCode, 0);
    const nlohmann::json lossAndPdl = {{{"op", "bone_loss"}, {"teeth", {24}}, {"depth_mm", 1.5}},
                                       {{"op", "pdl_thickness"}, {"tooth", 24}, {"thickness_mm", 0.3}}};
    nlohmann::json all = lossAndPdl;
    all.push_back({{"op", "extract"}, {"tooth", 25}, {"socket", "healed"}});
    const fs::path a = runWithEdits(dir, "a", lossAndPdl), b = runWithEdits(dir, "b", all);

    const test::RunFigures f = test::measureRun(b.string(), (dir / "case" / "input" / "mandible").string(), "mandible", {24});
    EXPECT_TRUE(f.validation.valid()) << "validation of the edited mesh";
    EXPECT_GE(f.quality.minDihedralDeg, 10.0 - 1e-6);
    EXPECT_NEAR(f.pdlThicknessMeanMm.at(24), 0.3, 0.015);
    const TetMesh meshB = readGmsh((b / "volumetric_meshes" / "mandible.msh").string());
    for (Label l : meshB.labels) ASSERT_TRUE(l != toothLabel(25) && l != pdlLabel(25)) << "label " << l << " left";

    // The crest drop and the healed socket, as run.json records them on the grids, and on the meshes:
    // the bone grew by the socket's volume.
    const nlohmann::json run = test::readJson(b / "run.json");
    ASSERT_EQ(run.at("edits").size(), 1u);
    const auto& applied = run.at("edits")[0].at("applied");
    ASSERT_EQ(applied.size(), 3u);
    EXPECT_NEAR(applied[0].at("teeth")[0].at("crest_drop_mm").get<double>(), 1.5, 0.1);
    // The socket: root and PDL of tooth 25 below the healed level, in the mesh before extraction.
    const auto& heal = applied[2];
    const auto vec = [](const nlohmann::json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); };
    const Vec3 up = vec(heal.at("axis").at("direction"));
    const Vec3 level = vec(heal.at("axis").at("origin")) + up * heal.at("fill_level_mm").get<double>();
    const TetMesh meshA = readGmsh((a / "volumetric_meshes" / "mandible.msh").string());
    const double socket = test::volumeBelowPlaneMm3(meshA, {toothLabel(25), pdlLabel(25)}, level, up);
    const Label bone = boneLabel(Jaw::Mandible);
    const double grown = labelVolumesMm3(meshB).at(bone) - labelVolumesMm3(meshA).at(bone);
    std::cout << "socket " << socket << " mm^3, bone grew " << grown << " mm^3 (" << heal.at("filled_volume_mm3")
              << " mm^3 of input socket filled on the grid)\n";
    EXPECT_NEAR(grown, socket, 0.05 * socket);

    const nlohmann::json report = test::readJson(b / "report" / "report.json");
    EXPECT_EQ(report.at("edits"), run.at("edits"));
    EXPECT_EQ(report.at("verdict").at("status"), "pass") << report.at("verdict").at("line");
    // The options record the edits in the form a --config file takes back (batches hash them).
    ASSERT_EQ(run.at("options").at("edits").size(), 3u);
    EXPECT_EQ(run.at("options").at("edits")[2], (nlohmann::json{{"op", "extract"}, {"tooth", 25}, {"socket", "healed"}}));
}

TEST(RunEdits, EditOnACarvedFolderGivesTheRunsMeshAndKeepsItsHistory) {
    const fs::path dir = test::scratchDir("edit-command");
    const auto ok = [&](const std::string& args, const std::string& log) {
        const test::CliResult r = test::runJawmesh(args, dir / log);
        EXPECT_EQ(r.exitCode, 0) << args << "\n" << r.output;
    };
    const std::string c = (dir / "case").string();
    ok("-q phantom " + c + " --teeth 2", "phantom.log");
    const nlohmann::json first = {{{"op", "bone_loss"}, {"teeth", {24, 25}}, {"depth_mm", 1.0}}};
    const nlohmann::json second = {{{"op", "pdl_thickness"}, {"tooth", 25}, {"thickness_mm", 0.3}}};
    std::ofstream(dir / "first.json") << nlohmann::json{{"edits", first}}.dump();
    std::ofstream(dir / "second.json") << nlohmann::json{{"edits", second}}.dump();
    nlohmann::json both = first;
    both.push_back(second[0]);
    std::ofstream(dir / "both.json") << nlohmann::json{{"edits", both}}.dump();

    // carve, edit twice, mesh; and the same edits in one run
    ok("-q carve " + c + " -o " + (dir / "carved").string() + " --voxel 0.1", "carve.log");
    ok("-q edit " + (dir / "carved" / "mandible" / "levelsets").string() + " --edits " + (dir / "first.json").string() +
           " -o " + (dir / "e1").string(), "e1.log");
    ok("-q edit " + (dir / "e1").string() + " --edits " + (dir / "second.json").string() + " -o " + (dir / "e2").string(),
       "e2.log");
    ok("-q run " + c + " --from-vdb " + (dir / "e2").string() + " -o " + (dir / "fromvdb").string(), "fromvdb.log");
    ok("-q run " + c + " --voxel 0.1 --edits " + (dir / "both.json").string() + " -o " + (dir / "direct").string(), "direct.log");

    const fs::path msh = fs::path("mandible") / "volumetric_meshes" / "mandible.msh";
    EXPECT_EQ(test::readText(dir / "fromvdb" / msh), test::readText(dir / "direct" / msh)) << "edit + --from-vdb and run --edits differ";
    const nlohmann::json history = test::readJson(dir / "e2" / "edits.json");
    ASSERT_EQ(history.size(), 2u);
    EXPECT_EQ(history[1].at("applied")[0].at("op"), "pdl_thickness");
    const nlohmann::json run = test::readJson(dir / "fromvdb" / "mandible" / "run.json");
    EXPECT_EQ(run.at("edits"), history);
    const nlohmann::json report = test::readJson(dir / "fromvdb" / "mandible" / "report" / "report.json");
    EXPECT_EQ(report.at("verdict").at("status"), "pass") << report.at("verdict").at("line");
    EXPECT_EQ(report.at("options").at("tooth_pdl_target_mm").at("25"), 0.3);
    // A folder without input level sets (an old one, or edited by hand) is refused, naming the file.
    fs::remove_all(dir / "e2" / "input");
    const test::CliResult r = test::runJawmesh("-q edit " + (dir / "e2").string() + " --edits " + (dir / "first.json").string() +
                                                   " -o " + (dir / "e3").string(), dir / "e3.log");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("input/carve.json"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "e3"));
}

TEST(RunEdits, BatchAppliesTheEditsToEveryCaseAndHashesThem) {
    const fs::path dir = test::scratchDir("batch-edits");
    ASSERT_EQ(test::runJawmesh("-q phantom " + (dir / "data" / "p1").string() + " --teeth 2", dir / "phantom.log").exitCode, 0);
    // A bone loss too: this test is the edits' run under the sanitizers (quickstart.sh robustness).
    std::ofstream(dir / "e.json") << R"({"edits": [{"op": "bone_loss", "teeth": [24], "depth_mm": 1.0},
                                                   {"op": "extract", "tooth": 25, "socket": "healed"}]})";
    const test::CliResult r = test::runJawmesh("-q batch " + (dir / "data").string() + " -o " + (dir / "out").string() +
                                                   " --config " + test::fastConfig() + " --edits " + (dir / "e.json").string(),
                                               dir / "batch.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(test::readJson(dir / "out" / "options.json").at("edits")[1].at("tooth"), 25);
    const nlohmann::json run = test::readJson(dir / "out" / "p1" / "mandible" / "run.json");
    EXPECT_EQ(run.at("edits")[0].at("applied")[1].at("op"), "extract");
    EXPECT_NEAR(run.at("edits")[0].at("applied")[0].at("teeth")[0].at("crest_drop_mm").get<double>(), 1.0, 0.1);
    EXPECT_GT(run.at("mesh").at("tets").get<std::size_t>(), 0u);
    for (const auto& t : run.at("carve").at("summary").at("teeth")) EXPECT_NE(t.at("unn"), 25);
}

TEST(RunEdits, WrongEditIsRefusedBeforeAnyWork) {
    const fs::path dir = test::scratchDir("run-edits-refused");
    ASSERT_EQ(test::runJawmesh("-q phantom " + (dir / "case").string() + " --teeth 2", dir / "phantom.log").exitCode, 0);
    std::ofstream(dir / "e.json") << R"({"edits": [{"op": "pdl_thickness", "tooth": 24, "thickness_mm": 0.3},
                                                   {"op": "extract", "tooth": 30}]})";
    const test::CliResult r = test::runJawmesh("-q run " + (dir / "case").string() + " -o " + (dir / "out").string() +
                                                   " --edits " + (dir / "e.json").string(),
                                               dir / "run.log");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("e.json: edits[1]: tooth 30 is not in this jaw"), std::string::npos) << r.output;
    EXPECT_TRUE(test::filesUnder(dir / "out").empty());
    EXPECT_TRUE(test::leftoversUnder(dir).empty());
}

}  // namespace
}  // namespace jawmesh
