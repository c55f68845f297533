// FEBio and PolyFEM decks validated structurally: well-formed XML / JSON, every referenced set,
// surface, material and file present, node and element counts matching the mesh.
#include "fe/ExteriorFaces.h"
#include "fe/FeDecks.h"
#include "fe/FeTestMeshes.h"
#include "fe/FebioWriter.h"
#include "fe/PolyfemWriter.h"
#include "fe/QuadraticTets.h"
#include "fe/support_MiniXml.h"
#include "io/Error.h"
#include "io/GmshReader.h"
#include "support/TestData.h"
#include "tet/GridTetMesh.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace jawmesh {
namespace {

using test::XmlNode;

std::size_t countCommaList(const std::string& text) {
    return text.empty() ? 0 : static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) + 1;
}

/// Checks an FEBio 4 file against the mesh it was written from.
void expectValidFebio(const std::string& path, const TetMesh& mesh, const FeScenario& s, int order) {
    const auto root = test::parseXml(test::readText(path));
    ASSERT_EQ(root->name, "febio_spec");
    EXPECT_EQ(root->attributes.at("version"), "4.0");
    const auto& meshNode = root->one("Mesh");
    const std::size_t expectedNodes = order == 2 ? quadraticTetMesh(mesh).nodes.size() : mesh.nodes.size();
    EXPECT_EQ(meshNode.one("Nodes").all("node").size(), expectedNodes);
    std::set<std::string> materials;
    for (const XmlNode* m : root->one("Material").all("material")) {
        materials.insert(m->attributes.at("name"));
        EXPECT_EQ(m->attributes.at("type"), "neo-Hookean");
    }
    // One element block per label, ids 1..T in order, domains in the same order with known materials.
    const auto blocks = meshNode.all("Elements");
    const auto domains = root->one("MeshDomains").all("SolidDomain");
    ASSERT_EQ(blocks.size(), std::set<Label>(mesh.labels.begin(), mesh.labels.end()).size());
    ASSERT_EQ(domains.size(), blocks.size());
    std::size_t elements = 0;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
        EXPECT_EQ(blocks[b]->attributes.at("type"), order == 2 ? "tet10" : "tet4");
        EXPECT_EQ(domains[b]->attributes.at("name"), blocks[b]->attributes.at("name"));
        EXPECT_TRUE(materials.count(domains[b]->attributes.at("mat")));
        for (const XmlNode* e : blocks[b]->all("elem")) {
            EXPECT_EQ(e->attributes.at("id"), std::to_string(++elements));
            ASSERT_EQ(countCommaList(e->text), order == 2 ? 10u : 4u);
        }
    }
    EXPECT_EQ(elements, mesh.tets.size());
    std::map<std::string, std::size_t> nodeSets, surfaces;
    for (const XmlNode* n : meshNode.all("NodeSet")) nodeSets[n->attributes.at("name")] = countCommaList(n->text);
    for (const XmlNode* n : meshNode.all("Surface")) surfaces[n->attributes.at("name")] = n->children.size();
    const auto bcs = root->one("Boundary").all("bc");
    ASSERT_EQ(bcs.size(), s.fixed.size());
    for (std::size_t i = 0; i < bcs.size(); ++i) {
        EXPECT_EQ(bcs[i]->attributes.at("type"), "zero displacement");
        ASSERT_TRUE(nodeSets.count(bcs[i]->attributes.at("node_set")));
        EXPECT_EQ(nodeSets[bcs[i]->attributes.at("node_set")], s.fixed[i].nodes.size());
    }
    const auto loads = root->one("Loads").all("surface_load");
    ASSERT_EQ(loads.size(), s.loads.size());
    std::set<std::string> controllers;
    for (const XmlNode* lc : root->one("LoadData").all("load_controller")) controllers.insert(lc->attributes.at("id"));
    for (std::size_t i = 0; i < loads.size(); ++i) {
        ASSERT_TRUE(surfaces.count(loads[i]->attributes.at("surface")));
        EXPECT_EQ(surfaces[loads[i]->attributes.at("surface")], s.loads[i].faces.size());
        EXPECT_TRUE(controllers.count(loads[i]->one("scale").attributes.at("lc")));
        // traction x area = the resultant
        std::istringstream t(loads[i]->one("traction").text);
        Vec3 traction;
        char comma;
        t >> traction.x() >> comma >> traction.y() >> comma >> traction.z();
        EXPECT_NEAR((traction * s.loads[i].areaMm2 - s.loads[i].totalForceN).norm(), 0.0, 1e-9);
    }
}

TEST(FebioWriter, TippingDeckIsWellFormedAndMatchesTheMesh) {
    const TetMesh mesh = test::gridJawBlock();
    const FeScenario s = tippingScenario(mesh, test::gridJawBlockAxes());
    const auto dir = test::scratchDir("fe-febio");
    for (int order : {1, 2}) {
        SCOPED_TRACE("order " + std::to_string(order));
        FebioOptions o;
        o.order = order;
        const std::string path = (dir / ("tipping" + std::to_string(order) + ".feb")).string();
        writeFebioDeck(mesh, s, MaterialTable(), path, o);
        expectValidFebio(path, mesh, s, order);
    }
}

TEST(FebioWriter, BitingDeckHasTheContactPairAndPartialConstraints) {
    const TetMesh mesh = test::withoutOutside(test::gridTetMesh(8, 4, 28, 0.5, [](const Vec3& p) -> Label {
        const bool lowerCrown = p.x() > 1 && p.x() < 3 && p.y() > 0.5 && p.y() < 1.5 && p.z() > 5 && p.z() < 6.4;
        const bool upperCrown = p.x() > 1 && p.x() < 3 && p.y() > 0.5 && p.y() < 1.5 && p.z() > 6.6 && p.z() < 8;
        if (lowerCrown) return toothLabel(24);
        if (upperCrown) return toothLabel(9);
        return p.z() < 5 ? kMandibleBoneLabel : p.z() > 8 ? kMaxillaBoneLabel : kOutsideLabel;
    }));
    const FeScenario s = bitingScenario(mesh);
    const auto dir = test::scratchDir("fe-febio-biting");
    writeFebioDeck(mesh, s, MaterialTable(), (dir / "biting.feb").string());
    expectValidFebio((dir / "biting.feb").string(), mesh, s, 1);
    const auto root = test::parseXml(test::readText((dir / "biting.feb").string()));
    const auto& pair = root->one("Mesh").one("SurfacePair");
    std::set<std::string> surfaces;
    for (const XmlNode* n : root->one("Mesh").all("Surface")) surfaces.insert(n->attributes.at("name"));
    EXPECT_TRUE(surfaces.count(pair.one("primary").text));
    EXPECT_TRUE(surfaces.count(pair.one("secondary").text));
    EXPECT_EQ(root->one("Contact").one("contact").attributes.at("surface_pair"), pair.attributes.at("name"));
    EXPECT_EQ(root->one("Boundary").all("bc")[1]->one("z_dof").text, "0");
}

TEST(PolyfemWriter, JsonParsesAndEveryReferencedFileAndSelectionExists) {
    const TetMesh mesh = test::gridJawBlock();
    const FeScenario s = tippingScenario(mesh, test::gridJawBlockAxes());
    const auto dir = test::scratchDir("fe-polyfem");
    const std::string jsonPath = (dir / "tipping_polyfem.json").string();
    const auto written = writePolyfemDeck(mesh, s, MaterialTable(), jsonPath);
    EXPECT_EQ(written.back(), jsonPath);
    const auto json = nlohmann::json::parse(test::readText(jsonPath));
    const auto& geometry = json.at("geometry").at(0);
    for (const char* key : {"mesh", "volume_selection", "surface_selection"})
        ASSERT_TRUE(std::filesystem::exists(dir / geometry.at(key).get<std::string>())) << key;

    // Mesh read back: same counts; body ids file = one label per element, in the file's order.
    const TetMesh back = readGmsh((dir / geometry.at("mesh").get<std::string>()).string());
    EXPECT_EQ(back.tets.size(), mesh.tets.size());
    EXPECT_EQ(back.nodes.size(), mesh.nodes.size());
    std::ifstream bodies(dir / geometry.at("volume_selection").get<std::string>());
    std::vector<Label> ids;
    for (Label l; bodies >> l;) ids.push_back(l);
    EXPECT_EQ(ids, back.labels);
    EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));

    // Every selected face is an exterior face of the written mesh, with a known id.
    std::set<std::array<std::int32_t, 3>> exterior;
    for (const ExteriorFace& f : exteriorFaces(back)) {
        auto key = f.nodes;
        std::sort(key.begin(), key.end());
        exterior.insert(key);
    }
    std::map<int, std::size_t> facesOfId;
    std::ifstream surfaces(dir / geometry.at("surface_selection").get<std::string>());
    for (int id; surfaces >> id;) {
        std::array<std::int32_t, 3> f;
        ASSERT_TRUE(surfaces >> f[0] >> f[1] >> f[2]);
        std::sort(f.begin(), f.end());
        EXPECT_TRUE(exterior.count(f));
        ++facesOfId[id];
    }
    const auto& bcs = json.at("boundary_conditions");
    ASSERT_EQ(bcs.at("dirichlet_boundary").size(), s.fixed.size());
    ASSERT_EQ(bcs.at("neumann_boundary").size(), s.loads.size());
    for (std::size_t i = 0; i < s.fixed.size(); ++i)
        EXPECT_EQ(facesOfId[bcs.at("dirichlet_boundary")[i].at("id").get<int>()], s.fixed[i].faces.size());
    for (std::size_t i = 0; i < s.loads.size(); ++i) {
        const auto& bc = bcs.at("neumann_boundary")[i];
        EXPECT_EQ(facesOfId[bc.at("id").get<int>()], s.loads[i].faces.size());
        const Vec3 traction(bc.at("value")[0].get<double>(), bc.at("value")[1].get<double>(), bc.at("value")[2].get<double>());
        EXPECT_NEAR((traction * s.loads[i].areaMm2 - s.loads[i].totalForceN).norm(), 0.0, 1e-12);
    }
    // Materials and orders for every body; quadratic PDL.
    std::set<Label> bodyIds(ids.begin(), ids.end());
    std::set<Label> materialIds;
    for (const auto& m : json.at("materials")) {
        materialIds.insert(m.at("id").get<Label>());
        EXPECT_EQ(m.at("type"), "NeoHookean");
    }
    EXPECT_EQ(materialIds, bodyIds);
    for (const auto& o : json.at("space").at("discr_order"))
        EXPECT_EQ(o.at("order").get<int>(), labelKind(o.at("id").get<Label>()) == LabelKind::Pdl ? 2 : 1);
    EXPECT_FALSE(json.at("contact").at("enabled").get<bool>());
}

TEST(FeDecks, TippingDecksWithComputedAxesLandInTheSimulationFolder) {
    const TetMesh mesh = test::gridJawBlock();
    const auto dir = test::scratchDir("fe-decks");
    std::vector<std::string> notes;
    const auto written = writeTippingDecks(mesh, {}, dir.string(), {}, &notes);
    // the notes the decks carry come back to the caller (a run puts uncertain axes in run.json)
    EXPECT_TRUE(std::count(notes.begin(), notes.end(), "tooth 24: axes computed from its shape"));
    EXPECT_NE(test::readText(dir / "simulation" / "tipping.inp").find("** note: tooth 24: axes computed from its shape"), std::string::npos);
    std::set<std::string> names;
    for (const auto& p : written) {
        EXPECT_TRUE(std::filesystem::exists(p)) << p;
        names.insert(std::filesystem::path(p).filename().string());
    }
    for (const char* n : {"tipping.inp", "tipping.feb", "tipping_polyfem.json", "tipping_polyfem.msh", "tipping_axes.json"})
        EXPECT_TRUE(names.count(n)) << n;
    EXPECT_EQ(std::filesystem::path(written[0]).parent_path().filename(), "simulation");
    // The computed axes of the box teeth: occlusal +z, distal away from the midline (x = 5).
    const auto axes = axesForMesh(mesh, {});
    ASSERT_EQ(axes.size(), 2u);
    EXPECT_GT(axes.at(24).occlusal.z(), 0.99);
    EXPECT_LT(axes.at(24).mesialDistal.x(), -0.99);
    EXPECT_GT(axes.at(25).mesialDistal.x(), 0.99);
    // Crown = top 45% of the 5.5 mm tall box tooth (z in [1.5, 7]): z from 4.525 to 7, centroid 5.7625.
    EXPECT_NEAR(axes.at(24).crownCentre.z(), 5.7625, 1e-6);
    EXPECT_NEAR(axes.at(24).crownCentre.x(), 3.0, 1e-6);
    FeDeckOptions bad;
    bad.formats = {"abaqus"};
    EXPECT_THROW(writeTippingDecks(mesh, {}, dir.string(), bad), Error);
}

}  // namespace
}  // namespace jawmesh
