// CalculiX decks solved by the real solver (ccx): C3D4 and C3D10 tipping of the grid jaw block.
// Every value checked is read back from ccx's own .dat and .frd files.
#include "fe/CalculixResults.h"
#include "fe/CalculixWriter.h"
#include "fe/FeTestMeshes.h"
#include "fe/QuadraticTets.h"
#include "fe/RunCalculix.h"
#include "fe/Scenario.h"
#include "io/Error.h"
#include "support/TestData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace jawmesh {
namespace {

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

struct Solved {
    nlohmann::json summary;
    std::map<std::int32_t, Vec3> frd;
    CalculixDat dat;
};

Solved solveTipping(int order, const std::string& dirName) {
    const TetMesh mesh = test::gridJawBlock();
    const FeScenario s = tippingScenario(mesh, test::gridJawBlockAxes());
    const auto dir = test::scratchDir(dirName);
    const std::string inp = (dir / "tipping.inp").string();
    CalculixOptions o;
    o.order = order;
    writeCalculixDeck(mesh, s, MaterialTable(), inp, o);
    const CalculixRun run = runCalculix(inp);
    Solved r;
    r.summary = calculixSummary(s, run, inp);
    if (run.status == "completed") {
        r.frd = readCalculixFrdDisplacements((dir / "tipping.frd").string());
        r.dat = readCalculixDat((dir / "tipping.dat").string());
    }
    return r;
}

void expectTippingResult(const Solved& r, std::size_t expectedNodes) {
    ASSERT_EQ(r.summary["status"], "completed") << r.summary.dump(2);
    // Every node of the deck has a finite displacement in the .frd.
    ASSERT_EQ(r.frd.size(), expectedNodes);
    double maxU = 0;
    for (const auto& [node, u] : r.frd) {
        ASSERT_TRUE(u.allFinite()) << "node " << node;
        maxU = std::max(maxU, u.norm());
    }
    EXPECT_GT(maxU, 1e-5);
    EXPECT_LT(maxU, 1.0);
    // Both loaded crowns move lingually (+y, against the labial axis -y); .dat and .frd agree.
    ASSERT_EQ(r.summary["teeth"].size(), 2u);
    for (const auto& t : r.summary["teeth"]) {
        SCOPED_TRACE("tooth " + std::to_string(t["unn"].get<int>()));
        EXPECT_GT(t["along_force_mm"].get<double>(), 0.5 * t["magnitude_mm"].get<double>());
        EXPECT_GT(t["displacement_mm"][1].get<double>(), 1e-5);
        const Vec3 fromFrd = r.frd.at(t["load_node"].get<std::int32_t>());
        EXPECT_NEAR(fromFrd.y(), t["displacement_mm"][1].get<double>(), 1e-5 * std::max(1.0, std::abs(fromFrd.y())) + 1e-9);
    }
    // Fixed base nodes stay put.
    EXPECT_EQ(r.frd.at(1).norm(), 0.0);  // node 1 is the grid origin, on the base
    // Stresses read back for every region, positive and finite.
    for (const char* region : {"bone_mandible", "tooth_24", "tooth_25", "pdl_24", "pdl_25"}) {
        SCOPED_TRACE(region);
        ASSERT_TRUE(r.summary["regions"].contains(region));
        const double maxVm = r.summary["regions"][region]["max_von_mises_mpa"].get<double>();
        EXPECT_TRUE(std::isfinite(maxVm));
        EXPECT_GT(maxVm, 0.0);
    }
}

TEST(Calculix, DeckHasRegionSetsNeoHookeConstantsAndOutputRequests) {
    const TetMesh mesh = test::gridJawBlock();
    const FeScenario s = tippingScenario(mesh, test::gridJawBlockAxes());
    const auto dir = test::scratchDir("fe-ccx-deck");
    writeCalculixDeck(mesh, s, MaterialTable(), (dir / "t.inp").string());
    const std::string deck = readText((dir / "t.inp").string());
    for (const char* needle : {"*ELEMENT, TYPE=C3D4, ELSET=tooth_24", "*ELEMENT, TYPE=C3D4, ELSET=pdl_25",
                               "*ELEMENT, TYPE=C3D4, ELSET=bone_mandible", "*NSET, NSET=fixed_base_mandible",
                               "*NSET, NSET=loadpt_tooth_24", "*HYPERELASTIC, NEO HOOKE", "*BOUNDARY", "*CLOAD",
                               "*NODE FILE", "*EL FILE", "*NODE PRINT, NSET=loadpts", "*EL PRINT, ELSET=pdl_24"})
        EXPECT_NE(deck.find(needle), std::string::npos) << needle;
    // PDL: E 68.9, nu 0.45 -> C10 = E / (4 (1 + nu)) = 11.8793..., D1 = 6 (1 - 2 nu) / E = 0.0087082...
    const Material pdl = MaterialTable().pdl;
    EXPECT_NEAR(neoHookeC10(pdl), 68.9 / 5.8, 1e-12);
    EXPECT_NEAR(neoHookeD1(pdl), 0.6 / 68.9, 1e-15);
    EXPECT_NE(deck.find("11.8793103448"), std::string::npos);
    CalculixOptions bad;
    bad.order = 3;
    EXPECT_THROW(writeCalculixDeck(mesh, s, MaterialTable(), (dir / "u.inp").string(), bad), Error);
}

TEST(Calculix, SolvesLinearTetTippingAndEveryCrownMovesLingually) {
    ASSERT_FALSE(findCalculix().empty()) << "ccx missing: install the Debian package calculix-ccx (quickstart.sh does)";
    const Solved r = solveTipping(1, "fe-ccx-c3d4");
    ASSERT_NO_FATAL_FAILURE(expectTippingResult(r, test::gridJawBlock().nodes.size()));
    std::cout << "C3D4: " << r.summary["seconds"] << " s, tooth 24 moved " << r.summary["teeth"][0]["magnitude_mm"] << " mm\n";
}

TEST(Calculix, SolvesQuadraticTetTippingWithSharedMidEdgeNodes) {
    ASSERT_FALSE(findCalculix().empty()) << "ccx missing: install the Debian package calculix-ccx (quickstart.sh does)";
    const Solved linear = solveTipping(1, "fe-ccx-c3d4-ref");
    const Solved r = solveTipping(2, "fe-ccx-c3d10");
    const TetMesh mesh = test::gridJawBlock();
    const std::size_t nodes = quadraticTetMesh(mesh).nodes.size();
    // Shared mid-edge nodes: ccx would report unconnected nodes (and zero stiffness) otherwise.
    ASSERT_NO_FATAL_FAILURE(expectTippingResult(r, nodes));
    // Quadratic tets are less stiff than linear ones on the same mesh, but of the same order.
    ASSERT_EQ(linear.summary["status"], "completed");
    for (std::size_t i = 0; i < 2; ++i) {
        const double ratio = r.summary["teeth"][i]["magnitude_mm"].get<double>() /
                             linear.summary["teeth"][i]["magnitude_mm"].get<double>();
        EXPECT_GT(ratio, 0.95);
        EXPECT_LT(ratio, 3.0);
    }
    std::cout << "C3D10: " << r.summary["seconds"] << " s, tooth 24 moved " << r.summary["teeth"][0]["magnitude_mm"] << " mm\n";
}

TEST(Calculix, ReadersRejectMissingAndMalformedOutput) {
    const auto dir = test::scratchDir("fe-ccx-bad");
    EXPECT_THROW(readCalculixDat((dir / "none.dat").string()), Error);
    EXPECT_THROW(readCalculixFrdDisplacements((dir / "none.frd").string()), Error);
    {
        std::ofstream bad(dir / "bad.dat");
        bad << " displacements (vx,vy,vz) for set LOADPTS and time  0.1000000E+01\n\n         5 -2.2E-03 oops\n";
    }
    EXPECT_THROW(readCalculixDat((dir / "bad.dat").string()), Error);
    {
        std::ofstream empty(dir / "empty.frd");
        empty << "    1C\n 9999\n";
    }
    EXPECT_THROW(readCalculixFrdDisplacements((dir / "empty.frd").string()), Error);
    EXPECT_NEAR(vonMises({1, 0, 0, 0, 0, 0}), 1.0, 1e-12);
    EXPECT_NEAR(vonMises({0, 0, 0, 1, 0, 0}), std::sqrt(3.0), 1e-12);
}

}  // namespace
}  // namespace jawmesh
