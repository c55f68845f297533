// The shared real cases: discovery, loading, STL welding on 1.69 M triangles, and the arch
// numbering rule checked against the published per-file numbering.
#include "io/Case.h"
#include "io/MeshIO.h"
#include "support/TestData.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

namespace jawmesh::test {
namespace {

/// Number of edges not shared by exactly two triangles (0 for a closed, edge-manifold surface).
std::size_t badEdges(const SurfaceMesh& m) {
    std::vector<std::pair<std::int32_t, std::int32_t>> edges;
    edges.reserve(m.triangles.size() * 3);
    for (const Tri& t : m.triangles)
        for (int j = 0; j < 3; ++j) {
            const std::int32_t a = t[static_cast<std::size_t>(j)], b = t[static_cast<std::size_t>((j + 1) % 3)];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    std::size_t bad = 0;
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        bad += (j - i) != 2;
        i = j;
    }
    return bad;
}

// Read speed is measured by bench/read_surface.sh, not asserted here.
TEST(RealCases, MandibleBoneStlIsWeldedAndClosed) {
    const std::string path = sharedData("openmandible/input/mandible/bone/mandible.stl");
    JAWMESH_REQUIRE_SHARED(path);
    const SurfaceMesh bone = readSurface(path);
    EXPECT_EQ(bone.triangles.size(), 1686074u);
    // Closed manifold surface (README): every edge in exactly two triangles, V - E + F = 2 - 2g.
    EXPECT_EQ(badEdges(bone), 0u);
    EXPECT_EQ((3 * bone.triangles.size()) % 2, 0u);
    const BBox box = boundingBox(bone);
    EXPECT_NEAR(box.min.x(), 84.35, 0.01);
    EXPECT_NEAR(box.max.y(), 190.14, 0.01);
    EXPECT_NEAR(signedVolume(bone), 46914.8, 5.0);
}

/// What a shared single-jaw case holds: its jaw, its tooth files (count, lowest and highest UNN),
/// whether it has an axes file, and its bone's triangle count.
struct SharedCase {
    std::string folder;
    Jaw jaw;
    std::size_t teeth;
    int firstUnn, lastUnn;
    bool hasAxes;
    std::size_t boneTriangles;
};

/// Discovers and reads the case, asserting what `expected` says of it (gtest EXPECTs); the
/// surfaces read. Throws when the case does not have exactly one jaw.
JawSurfaces readSharedCase(const SharedCase& expected) {
    const CaseInfo info = discoverCase(sharedData(expected.folder));
    if (info.jaws.size() != 1) throw std::runtime_error(expected.folder + ": " + std::to_string(info.jaws.size()) + " jaws");
    const JawCase& jc = info.jaws[0];
    EXPECT_EQ(jc.jaw, expected.jaw);
    EXPECT_EQ(jc.toothPaths.size(), expected.teeth);
    if (!jc.toothPaths.empty()) {
        EXPECT_EQ(jc.toothPaths.begin()->first, expected.firstUnn);
        EXPECT_EQ(jc.toothPaths.rbegin()->first, expected.lastUnn);
    }
    EXPECT_EQ(!jc.axesPath.empty(), expected.hasAxes);
    JawSurfaces s = loadJaw(jc);
    EXPECT_EQ(s.bone.triangles.size(), expected.boneTriangles);
    return s;
}

TEST(RealCases, OpenMandibleCaseHas14TeethAndItsBone) {
    JAWMESH_REQUIRE_SHARED(sharedData("openmandible"));
    const JawSurfaces s = readSharedCase({"openmandible", Jaw::Mandible, 14, 18, 31, false, 1686074});
    ASSERT_EQ(s.teeth.size(), 14u);
    EXPECT_EQ(s.teeth.at(18).triangles.size(), 53486u);
    EXPECT_EQ(s.teeth.at(31).triangles.size(), 54738u);
    for (const auto& [unn, tooth] : s.teeth) {
        EXPECT_EQ(badEdges(tooth), 0u) << "tooth " << unn;
        EXPECT_GT(signedVolume(tooth), 250.0) << "tooth " << unn;
    }
    EXPECT_TRUE(s.notes.empty());
}

TEST(RealCases, P26MaxillaHas15TeethWithAxes) {
    JAWMESH_REQUIRE_SHARED(sharedData("p26-maxilla-teeth"));
    const JawSurfaces s = readSharedCase({"p26-maxilla-teeth", Jaw::Maxilla, 15, 1, 15, true, 567204});
    ASSERT_EQ(s.axes.size(), 15u);
    for (const auto& [unn, a] : s.axes) {
        ASSERT_TRUE(s.teeth.count(unn));
        // The crown centre lies within the tooth's box, and the axes are unit and near-orthogonal.
        const BBox box = boundingBox(s.teeth.at(unn));
        EXPECT_TRUE((a.crownCentre.array() >= box.min.array() - 0.5).all() && (a.crownCentre.array() <= box.max.array() + 0.5).all())
            << "tooth " << unn;
        EXPECT_NEAR(a.occlusal.norm(), 1.0, 1e-9);
        EXPECT_LT(std::abs(a.occlusal.dot(a.mesialDistal)), 0.2) << "tooth " << unn;
    }
    EXPECT_TRUE(s.notes.empty());
}

/// Combines a real case's teeth into one mesh, numbers them along the arch and compares with the
/// dataset's own numbering.
void checkArchNumbering(const std::string& caseDir) {
    const JawCase jc = discoverCase(caseDir).jaws.at(0);
    const JawSurfaces s = loadJaw(jc);
    SurfaceMesh all;
    for (const auto& [unn, tooth] : s.teeth) append(all, tooth);
    std::vector<std::string> notes;
    const auto numbered = numberTeethAlongArch(all, jc.jaw, s.bone, &notes);
    ASSERT_EQ(notes.size(), 1u);
    std::printf("%s\n", notes[0].c_str());
    EXPECT_NE(notes[0].find("bone"), std::string::npos);
    ASSERT_EQ(numbered.size(), s.teeth.size());
    for (const auto& [unn, tooth] : s.teeth) {
        ASSERT_TRUE(numbered.count(unn)) << "UNN " << unn << " not assigned";
        EXPECT_EQ(numbered.at(unn).triangles.size(), tooth.triangles.size()) << "UNN " << unn;
        EXPECT_NEAR(signedVolume(numbered.at(unn)), signedVolume(tooth), 1e-6 * std::abs(signedVolume(tooth))) << "UNN " << unn;
    }
}

TEST(RealCases, ArchNumberingReproducesTheMandibleNumbering) {
    JAWMESH_REQUIRE_SHARED(sharedData("openmandible"));
    checkArchNumbering(sharedData("openmandible"));
}

TEST(RealCases, ArchNumberingReproducesTheMaxillaNumbering) {
    JAWMESH_REQUIRE_SHARED(sharedData("p26-maxilla-teeth"));
    checkArchNumbering(sharedData("p26-maxilla-teeth"));
}

}  // namespace
}  // namespace jawmesh::test
