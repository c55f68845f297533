// An implant in place of a tooth (issue #24, `"op": "implant"`) on the 2-tooth phantom at 0.1 mm:
// the mesh holds implant_25 and no tooth or PDL 25, the implant shares faces and nodes with the
// bone (fused, no gap), its body below the platform has the cylinder's volume, labels.json and
// the CalculiX deck carry it as titanium, and under the tipping load its crown moves less than
// the natural tooth beside it (no PDL). (Refusals: tests/levelset/test_jaw_edits.cpp.)
#include "io/GmshReader.h"
#include "io/Labels.h"
#include "support/TestData.h"
#include "support/TextFiles.h"
#include "support_CliRun.h"
#include "support_RunChecks.h"
#include "tet/ElementQuality.h"
#include "tet/ValidateTetMesh.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

Vec3 vec(const nlohmann::json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

/// Load-point displacement of each loaded tooth in the CalculiX summary of a tipping solve, mm.
std::map<int, double> loadPointDisplacementMm(const fs::path& jawDir) {
    std::map<int, double> out;
    const nlohmann::json summary = test::readJson(jawDir / "simulation" / "tipping_calculix_summary.json");
    for (const auto& t : summary.at("teeth"))
        out[t.at("unn").get<int>()] = t.at("magnitude_mm").get<double>();
    return out;
}

TEST(RunImplant, ImplantIsFusedToTheBoneWithItsBodysVolumeAndMovesLessThanATooth) {
    const fs::path dir = test::scratchDir("run-implant");
    ASSERT_EQ(test::runJawmesh("-q phantom " + (dir / "case").string() + " --teeth 2", dir / "phantom.log").exitCode, 0);
    std::ofstream(dir / "implant.json") << R"({"edits": [{"op": "implant", "tooth": 25, "diameter_mm": 4.1, "length_mm": 8.0}]})";
    const test::CliResult r = test::runJawmesh("-q run " + (dir / "case").string() + " -o " + (dir / "out").string() +
                                                   " --voxel 0.1 --edits " + (dir / "implant.json").string(),
                                               dir / "run.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const fs::path jawDir = dir / "out" / "mandible";
    const TetMesh mesh = readGmsh((jawDir / "volumetric_meshes" / "mandible.msh").string());
    const ValidationReport v = validateTetMesh(mesh, {24, 25});
    EXPECT_TRUE(v.valid()) << toJson(v).dump(1);
    EXPECT_GE(measureQuality(mesh, 10.0).minDihedralDeg, 10.0 - 1e-6);
    const Label implant = implantLabel(25), bone = boneLabel(Jaw::Mandible);
    EXPECT_GT(v.tetsPerLabel.count(implant), 0u);
    EXPECT_EQ(v.tetsPerLabel.count(toothLabel(25)) + v.tetsPerLabel.count(pdlLabel(25)), 0u);
    // Fused: faces and nodes shared with the bone, none with tooth 24 or its PDL.
    EXPECT_GT(v.interfaceFacesPerPair.count({bone, implant}) ? v.interfaceFacesPerPair.at({bone, implant}) : 0u, 500u);
    EXPECT_EQ(v.interfaceFacesPerPair.count({toothLabel(24), implant}) + v.interfaceFacesPerPair.count({pdlLabel(24), implant}), 0u);

    // The body below the platform: the cylinder's pi r^2 L within 2 %.
    const nlohmann::json run = test::readJson(jawDir / "run.json");
    const nlohmann::json& placed = run.at("edits")[0].at("applied")[0];
    const double body = placed.at("body_volume_mm3").get<double>();
    EXPECT_NEAR(body, M_PI * 2.05 * 2.05 * 8.0, 1e-9);
    const Vec3 up = vec(placed.at("axis").at("direction"));
    const double meshed = test::volumeBelowPlaneMm3(mesh, {implant}, vec(placed.at("platform_centre")), up);
    std::cout << "implant body below the platform: " << meshed << " mm^3 meshed, " << body << " mm^3 analytic\n";
    EXPECT_NEAR(meshed, body, 0.02 * body);

    const nlohmann::json labels = test::readJson(jawDir / "volumetric_meshes" / "labels.json");
    EXPECT_NE(labels.dump().find("\"implant\""), std::string::npos) << labels.dump();

    // Titanium in the deck; the fused crown moves less than the natural tooth 24 under the same load.
    const test::CliResult fe = test::runJawmesh(
        "-q fe " + jawDir.string() + " --scenario tipping --format inp --order 1 --solve", dir / "fe.log");
    ASSERT_EQ(fe.exitCode, 0) << fe.output;
    const std::string deck = test::readText(jawDir / "simulation" / "tipping.inp");
    EXPECT_NE(deck.find("*MATERIAL, NAME=implant"), std::string::npos);
    EXPECT_NE(deck.find("ELSET=implant_25, MATERIAL=implant"), std::string::npos);
    const std::map<int, double> moved = loadPointDisplacementMm(jawDir);
    ASSERT_TRUE(moved.count(24) && moved.count(25));
    std::cout << "tipping load point: tooth 24 " << moved.at(24) << " mm, implant 25 " << moved.at(25) << " mm\n";
    EXPECT_LT(moved.at(25), moved.at(24));
}

}  // namespace
}  // namespace jawmesh
