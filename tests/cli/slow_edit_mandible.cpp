// What-if edits on the shared mandible (issue #24), measured on the output meshes of two finished
// runs: JAWMESH_MANDIBLE_RUN=<out>/mandible (as made, `quickstart.sh mandible-test`) and
// JAWMESH_MANDIBLE_EDIT_RUN=<out>/mandible (the same case with tests/data/mandible_what_if.json:
// 2 mm of bone loss around teeth 23-26, tooth 30 extracted with a healed socket, PDL 24 at
// 0.3 mm, an implant of 4.1 x 10 mm in place of tooth 19). Without them the tests skip.
#include "io/GmshReader.h"
#include "io/Labels.h"
#include "support/TestData.h"
#include "support/TextFiles.h"
#include "support_CliRun.h"
#include "support_RunChecks.h"
#include "tet/ValidateTetMesh.h"
#include "tet/ElementQuality.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <optional>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

struct Runs {
    std::string before, after;
};

std::optional<Runs> runs() {
    const char* before = std::getenv("JAWMESH_MANDIBLE_RUN");
    const char* after = std::getenv("JAWMESH_MANDIBLE_EDIT_RUN");
    if (!before || !after) return std::nullopt;
    return Runs{before, after};
}

TetMesh readMesh(const std::string& jawDir) { return readGmsh(jawDir + "/volumetric_meshes/mandible.msh"); }

Vec3 vec(const nlohmann::json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

/// The applied edit with this op, from run.json's history.
nlohmann::json applied(const std::string& jawDir, const std::string& op) {
    const nlohmann::json run = test::readJson(fs::path(jawDir) / "run.json");
    for (const auto& record : run.at("edits"))
        for (const auto& e : record.at("applied"))
            if (e.at("op") == op) return e;
    throw std::runtime_error(jawDir + ": no " + op + " edit in run.json");
}

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); }

/// Highest point of a region along an axis, mm.
double topOf(const TetMesh& mesh, Label label, const Vec3& origin, const Vec3& up) {
    double top = -1e9;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (mesh.labels[t] == label)
            for (int k = 0; k < 4; ++k) top = std::max(top, (mesh.nodes[mesh.tets[t][k]] - origin).dot(up));
    return top;
}

#define REQUIRE_RUNS()                                                                                        \
    const auto r = runs();                                                                                    \
    if (!r) GTEST_SKIP() << "set JAWMESH_MANDIBLE_RUN and JAWMESH_MANDIBLE_EDIT_RUN (quickstart.sh mandible-test)"

TEST(SlowEditMandible, EditedMeshMeetsEveryMeshCheckWithItsOwnPdlTarget) {
    REQUIRE_RUNS();
    const std::string input = test::sharedData("openmandible/input/mandible");
    JAWMESH_REQUIRE_SHARED(input);
    std::vector<int> teeth = test::teethIn(input + "/teeth");
    for (int gone : {19, 30}) teeth.erase(std::remove(teeth.begin(), teeth.end(), gone), teeth.end());
    ASSERT_EQ(teeth.size(), 12u);
    const test::RunFigures f = test::measureRun(r->after, input, "mandible", teeth);
    EXPECT_TRUE(f.validation.valid()) << "conformal, manifold, every tooth with its PDL";
    EXPECT_GE(f.quality.minDihedralDeg, 10.0 - 1e-6);
    EXPECT_EQ(f.quality.belowDihedralThreshold, 0u);
    EXPECT_LE(f.quality.tets, 800000u);
    for (int unn : teeth) {
        const double target = unn == 24 ? 0.3 : 0.2, tolerance = unn == 24 ? 0.015 : 0.01;
        std::cout << "tooth " << unn << ": PDL mean " << f.pdlThicknessMeanMm.at(unn) << " mm, Hausdorff "
                  << f.toothHausdorffMm.at(unn) << " mm\n";
        EXPECT_NEAR(f.pdlThicknessMeanMm.at(unn), target, tolerance) << "tooth " << unn;
        // A thicker PDL takes its share from the root: 0.3 mm erodes it 0.05 mm more than 0.2 mm.
        EXPECT_LE(f.toothHausdorffMm.at(unn), unn == 24 ? 0.2 : 0.15) << "tooth " << unn;
    }
}

TEST(SlowEditMandible, BoneLossDropsTheCrestTwoMillimetresAndCapsThePdlThere) {
    REQUIRE_RUNS();
    const TetMesh before = readMesh(r->before), after = readMesh(r->after);
    const nlohmann::json loss = applied(r->after, "bone_loss");
    ASSERT_EQ(loss.at("depth_mm"), 2.0);
    for (const auto& t : loss.at("teeth")) {
        const int unn = t.at("tooth");
        const Vec3 origin = vec(t.at("axis").at("origin")), up = vec(t.at("axis").at("direction"));
        const auto crestBefore = test::crestHeightsMm(before, kMandibleBoneLabel, unn, origin, up);
        const auto crestAfter = test::crestHeightsMm(after, kMandibleBoneLabel, unn, origin, up);
        ASSERT_GE(crestBefore.size(), 30u) << "tooth " << unn;
        ASSERT_GE(crestAfter.size(), 30u) << "tooth " << unn;
        const double drop = mean(crestBefore) - mean(crestAfter);
        const double pdlTopBefore = topOf(before, pdlLabel(unn), origin, up), pdlTopAfter = topOf(after, pdlLabel(unn), origin, up);
        const double crestTop = *std::max_element(crestAfter.begin(), crestAfter.end());
        std::cout << "tooth " << unn << ": crest " << mean(crestBefore) << " -> " << mean(crestAfter) << " mm (drop " << drop
                  << "), PDL top " << pdlTopBefore << " -> " << pdlTopAfter << " mm, highest new crest " << crestTop << " mm\n";
        EXPECT_NEAR(drop, 2.0, 0.1) << "tooth " << unn;
        EXPECT_LT(pdlTopAfter, pdlTopBefore - 1.5) << "tooth " << unn << ": the PDL did not follow the crest";
        EXPECT_LE(pdlTopAfter, crestTop + 0.5) << "tooth " << unn << ": PDL above the new crest";
    }
}

TEST(SlowEditMandible, HealedExtractionTurnsTheSocketIntoBone) {
    REQUIRE_RUNS();
    const TetMesh before = readMesh(r->before), after = readMesh(r->after);
    for (Label l : after.labels) ASSERT_TRUE(l != toothLabel(30) && l != pdlLabel(30)) << "label " << l << " left";
    const nlohmann::json heal = applied(r->after, "extract");
    ASSERT_EQ(heal.at("tooth"), 30);
    const Vec3 up = vec(heal.at("axis").at("direction"));
    const Vec3 level = vec(heal.at("axis").at("origin")) + up * heal.at("fill_level_mm").get<double>();
    // The socket: root and PDL of tooth 30 below the healed level, before the extraction.
    const double socket = test::volumeBelowPlaneMm3(before, {toothLabel(30), pdlLabel(30)}, level, up);
    // The bone between the bisectors of 29-30 and 30-31 (the bone loss, at 23-26, is far from it).
    const auto centroid = [&](Label l) {
        Vec3 c = Vec3::Zero();
        double n = 0;
        for (std::size_t t = 0; t < before.tets.size(); ++t)
            if (before.labels[t] == l)
                for (int k = 0; k < 4; ++k) c += before.nodes[before.tets[t][k]], n += 1;
        return Vec3(c / n);
    };
    const Vec3 c29 = centroid(toothLabel(29)), c30 = centroid(toothLabel(30)), c31 = centroid(toothLabel(31));
    const Vec3 along = (c31 - c29).normalized();
    const auto slab = [&](const TetMesh& m) {
        return test::volumeBelowPlaneMm3(m, {kMandibleBoneLabel}, (c30 + c31) / 2, along) -
               test::volumeBelowPlaneMm3(m, {kMandibleBoneLabel}, (c29 + c30) / 2, along);
    };
    const double grown = slab(after) - slab(before);
    std::cout << "socket of tooth 30 below the healed level " << socket << " mm^3; bone around it grew " << grown
              << " mm^3 (" << heal.at("filled_volume_mm3") << " mm^3 of the input socket filled on the grid)\n";
    EXPECT_NEAR(grown, socket, 0.05 * socket);
}

/// Load-point displacement (mm) of tooth `unn` under `jawmesh fe`'s tipping load, solved by CalculiX
/// in the run's own folder.
double tippingDisplacementMm(const std::string& jawDir, int unn) {
    const test::CliResult fe = test::runJawmesh("-q fe " + jawDir + " --scenario tipping --format inp --order 1 --solve",
                                                fs::path(jawDir) / "simulation-tipping.log");
    if (fe.exitCode != 0) throw std::runtime_error(jawDir + ": jawmesh fe failed: " + fe.output);
    const nlohmann::json summary = test::readJson(fs::path(jawDir) / "simulation" / "tipping_calculix_summary.json");
    for (const auto& t : summary.at("teeth"))
        if (t.at("unn") == unn) return t.at("magnitude_mm").get<double>();
    throw std::runtime_error(jawDir + ": tooth " + std::to_string(unn) + " was not loaded");
}

TEST(SlowEditMandible, ImplantTakesToothNineteensPlaceFusedAndMovesLessUnderTipping) {
    REQUIRE_RUNS();
    const TetMesh after = readMesh(r->after);
    const Label implant = implantLabel(19);
    for (Label l : after.labels) ASSERT_TRUE(l != toothLabel(19) && l != pdlLabel(19)) << "label " << l << " left";
    const ValidationReport v = validateTetMesh(after, {19});
    EXPECT_TRUE(v.valid()) << toJson(v).dump(1);
    ASSERT_TRUE(v.tetsPerLabel.count(implant));
    const std::size_t fused = v.interfaceFacesPerPair.count({kMandibleBoneLabel, implant})
                                  ? v.interfaceFacesPerPair.at({kMandibleBoneLabel, implant}) : 0;
    EXPECT_GT(fused, 1000u) << "faces shared by the implant and the bone";
    // The body below the platform against the cylinder's volume.
    const nlohmann::json placed = applied(r->after, "implant");
    const double body = placed.at("body_volume_mm3").get<double>();
    EXPECT_NEAR(body, M_PI * 2.05 * 2.05 * 10.0, 1e-9);
    const double meshed = test::volumeBelowPlaneMm3(after, {implant}, vec(placed.at("platform_centre")),
                                                    vec(placed.at("axis").at("direction")));
    std::cout << "implant 19: body below the platform " << meshed << " mm^3 meshed, " << body << " mm^3 analytic ("
              << 100.0 * (meshed - body) / body << " %); " << fused << " faces fused to the bone\n";
    EXPECT_NEAR(meshed, body, 0.02 * body);
    // The same tipping load on the natural tooth 19 (the unedited run) and on the implant's crown.
    const double natural = tippingDisplacementMm(r->before, 19), implanted = tippingDisplacementMm(r->after, 19);
    std::cout << "tipping load point of 19: natural tooth " << natural << " mm, implant " << implanted << " mm\n";
    EXPECT_LT(implanted, natural);
}

}  // namespace
}  // namespace jawmesh
