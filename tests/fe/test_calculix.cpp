// CalculiX decks solved by the real solver (ccx): C3D4 and C3D10 tipping of the grid jaw block.
// Every value checked is read back from ccx's own .dat and .frd files.
#include "fe/CalculixResults.h"
#include "fe/CalculixWriter.h"
#include "fe/CloseBite.h"
#include "fe/ExteriorFaces.h"
#include "fe/FeTestMeshes.h"
#include "fe/QuadraticTets.h"
#include "fe/RunCalculix.h"
#include "fe/Scenario.h"
#include "io/Error.h"
#include "support/TestData.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

namespace jawmesh {
namespace {

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
    r.summary = calculixSummary(s, run, inp, &mesh);
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
        // The load point is a node of the tooth: the tooth's largest displacement is at least its.
        EXPECT_GE(t["tooth_max_displacement_mm"].get<double>(), t["magnitude_mm"].get<double>() * (1 - 1e-6));
        // In its socket: the load point relative to the socket's mean motion is at most the
        // tooth's largest, which is at most its absolute largest plus the socket's own motion.
        const auto& sm = t["socket_mean_displacement_mm"];
        const Vec3 socket(sm[0].get<double>(), sm[1].get<double>(), sm[2].get<double>());
        const double inSocket = t["tooth_max_displacement_in_socket_mm"].get<double>();
        EXPECT_GT(inSocket, 0.0);
        EXPECT_GE(inSocket, (fromFrd - socket).norm() * (1 - 1e-6));
        EXPECT_LE(inSocket, (t["tooth_max_displacement_mm"].get<double>() + socket.norm()) * (1 + 1e-6));
        // The tooth moves more than the bone holding it (the PDL is 20-30x softer).
        EXPECT_LT(socket.norm(), t["tooth_max_displacement_mm"].get<double>());
    }
    // All PDL elements together: both PDLs' elements, median below the 99.99th percentile.
    const auto& pdl = r.summary["pdl"];
    EXPECT_EQ(pdl["elements"].get<std::size_t>(),
              r.summary["regions"]["pdl_24"]["elements"].get<std::size_t>() + r.summary["regions"]["pdl_25"]["elements"].get<std::size_t>());
    EXPECT_GT(pdl["median_von_mises_mpa"].get<double>(), 0.0);
    EXPECT_GE(pdl["p9999_over_median"].get<double>(), 1.0);
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
    const std::string deck = test::readText((dir / "t.inp").string());
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

TEST(Calculix, BitingDeckHasCrownSurfacesOnExteriorFacesAndAContactPair) {
    const TetMesh mesh = test::twoCrownBite();
    const FeScenario s = bitingScenario(mesh);
    const auto dir = test::scratchDir("fe-ccx-biting-deck");
    writeCalculixDeck(mesh, s, MaterialTable(), (dir / "biting.inp").string());
    const std::string deck = test::readText((dir / "biting.inp").string());
    for (const char* needle : {"*SURFACE, NAME=crowns_mandible, TYPE=ELEMENT", "*SURFACE, NAME=crowns_maxilla, TYPE=ELEMENT",
                               "*SURFACE INTERACTION, NAME=occlusal_contact", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
                               "*CONTACT PAIR, INTERACTION=occlusal_contact, TYPE=SURFACE TO SURFACE\ncrowns_mandible, crowns_maxilla",
                               "fixed_top_maxilla, 3, 3", "base_mandible, 1, 1", "base_mandible, 2, 2", "*CLOAD"})
        EXPECT_NE(deck.find(needle), std::string::npos) << needle;
    EXPECT_EQ(deck.find("base_mandible, 3, 3"), std::string::npos);  // free vertically
    // Every surface line names a face (by Abaqus's S1..S4 numbering of the element's own nodes)
    // that is an exterior face of a tooth of that jaw.
    std::set<std::array<std::int32_t, 3>> exteriorTooth;
    for (const ExteriorFace& f : exteriorFaces(mesh)) {
        if (labelKind(f.label) != LabelKind::Tooth) continue;
        std::array<std::int32_t, 3> key = f.nodes;
        std::sort(key.begin(), key.end());
        exteriorTooth.insert(key);
    }
    const std::array<std::array<int, 3>, 4> abaqusFaces = {{{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}}};
    std::istringstream in(deck);
    std::string line, surface;
    std::map<std::string, std::size_t> faceCount;
    while (std::getline(in, line)) {
        if (line.rfind("*SURFACE, NAME=", 0) == 0) {
            surface = line.substr(15, line.find(',', 15) - 15);
            continue;
        }
        if (line.empty() || line[0] == '*') surface.clear();
        if (surface.empty() || line.empty() || line[0] == '*') continue;
        const std::int32_t element = std::stoi(line.substr(0, line.find(',')));
        const int face = std::stoi(line.substr(line.find('S') + 1));
        ASSERT_GE(face, 1);
        ASSERT_LE(face, 4);
        const Tet& tet = mesh.tets[static_cast<std::size_t>(element - 1)];
        std::array<std::int32_t, 3> key;
        for (std::size_t i = 0; i < 3; ++i) key[i] = tet[static_cast<std::size_t>(abaqusFaces[static_cast<std::size_t>(face - 1)][i])];
        std::sort(key.begin(), key.end());
        EXPECT_TRUE(exteriorTooth.count(key)) << line;
        const Label label = mesh.labels[static_cast<std::size_t>(element - 1)];
        EXPECT_EQ("crowns_" + jawName(jawOfTooth(labelUnn(label))), surface);
        ++faceCount[surface];
    }
    EXPECT_EQ(faceCount["crowns_mandible"] + faceCount["crowns_maxilla"], exteriorTooth.size());
}

// The biting deck runs in CalculiX: it reads the contact definitions, and with the crowns brought
// into contact (the mandible moved up by their 0.5 mm gap) the 200 N pass through them.
TEST(Calculix, SolvesTheBitingDeckWithContactOnTwoCrowns) {
    ASSERT_FALSE(findCalculix().empty()) << "ccx missing: install the Debian package calculix-ccx (quickstart.sh does)";
    const FeScenario s = bitingScenario(test::twoCrownBite());
    ASSERT_NEAR((s.mandibleOffsetMm - Vec3(0, 0, 0.5)).norm(), 0.0, 1e-9);
    const TetMesh mesh = withMandibleMoved(test::twoCrownBite(), s.mandibleOffsetMm);
    const auto dir = test::scratchDir("fe-ccx-biting");
    const std::string inp = (dir / "biting.inp").string();
    writeCalculixDeck(mesh, s, MaterialTable(), inp);
    const CalculixRun run = runCalculix(inp);
    const nlohmann::json summary = calculixSummary(s, run, inp);
    std::cout << summary.dump(2) << "\n";
    EXPECT_EQ(test::readText(run.logPath).find("*ERROR"), std::string::npos) << test::readText(run.logPath);
    ASSERT_EQ(run.status, "completed") << run.message;
    const auto frd = readCalculixFrdDisplacements((dir / "biting.frd").string());
    // The crowns touch from the start: the lower crown's top rises only by what the maxilla and the
    // contact penalty yield (well under the 0.5 mm gap closed beforehand), and it does rise.
    double lowerTopRise = 0;
    for (std::size_t v = 0; v < mesh.nodes.size(); ++v)
        if (std::abs(mesh.nodes[v].z() - 6.5) < 1e-9 && mesh.nodes[v].x() > 1 && mesh.nodes[v].x() < 3 &&
            frd.count(static_cast<std::int32_t>(v + 1)))
            lowerTopRise = std::max(lowerTopRise, frd.at(static_cast<std::int32_t>(v + 1)).z());
    EXPECT_GT(lowerTopRise, 0.0);
    EXPECT_LT(lowerTopRise, 0.25);
    EXPECT_GT(summary["regions"]["bone_maxilla"]["max_von_mises_mpa"].get<double>(), 0.0);
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
