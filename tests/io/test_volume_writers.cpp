// Volume-mesh writers: MSH 4.1 (ASCII, binary, mixed Tet4/Tet10) read back with readGmsh, VTU,
// Medit, labels.json; meshio cross-check when Python's meshio is installed.
#include "io/Error.h"
#include "io/GmshReader.h"
#include "io/GmshWriter.h"
#include "io/LabelsJson.h"
#include "io/MeditWriter.h"
#include "io/VtuWriter.h"
#include "support/TestData.h"
#include "tet/GridTetMesh.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

using namespace jawmesh;
using namespace jawmesh::test;
namespace fs = std::filesystem;

namespace {

TetMesh smallJaw() {
    // Irrational spacing so coordinates are not short decimals (exercises exact round trips).
    return gridTetMesh(6, 3, 3, 0.1 * std::sqrt(2.0), [](const Vec3& p) {
        if (p.z() < 0.2) return kMandibleBoneLabel;
        if (p.x() < 0.3) return toothLabel(24);
        if (p.x() < 0.6) return pdlLabel(24);
        return toothLabel(25);
    });
}

void expectSameMesh(const TetMesh& a, const TetMesh& b) {
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (std::size_t i = 0; i < a.nodes.size(); ++i) EXPECT_EQ(a.nodes[i], b.nodes[i]) << "node " << i;
    EXPECT_EQ(a.tets, b.tets);
    EXPECT_EQ(a.labels, b.labels);
}

/// A Python interpreter with meshio, or "" (the Debian package goes to /usr/bin/python3).
std::string pythonWithMeshio() {
    for (const char* py : {"python3", "/usr/bin/python3"}) {
        const std::string cmd = std::string(py) + " -c \"import meshio\" > /dev/null 2>&1";
        if (std::system(cmd.c_str()) == 0) return py;
    }
    return "";
}

std::string run(const std::string& cmd) {
    std::string out;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return out;
    char buf[256];
    while (fgets(buf, sizeof buf, p)) out += buf;
    pclose(p);
    return out;
}

}  // namespace

TEST(GmshWriter, AsciiAndBinaryRoundTrip) {
    const auto dir = scratchDir("gmsh-roundtrip");
    const TetMesh mesh = smallJaw();
    for (bool binary : {false, true}) {
        const fs::path path = dir / (binary ? "b.msh" : "a.msh");
        GmshWriteOptions o;
        o.binary = binary;
        writeGmsh(mesh, path.string(), o);
        expectSameMesh(mesh, readGmsh(path.string()));
        const std::string text = test::readText(path);
        EXPECT_NE(text.find("3 124 \"tooth_24\""), std::string::npos);
        EXPECT_NE(text.find("3 224 \"pdl_24\""), std::string::npos);
        EXPECT_NE(text.find("3 1 \"bone_mandible\""), std::string::npos);
        EXPECT_NE(text.find(binary ? "4.1 1 8" : "4.1 0 8"), std::string::npos);
    }
    for (const auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos);
}

TEST(GmshWriter, MixedQuadraticTets) {
    const auto dir = scratchDir("gmsh-tet10");
    const TetMesh lin = smallJaw();
    MixedTetMesh mixed;
    mixed.nodes = lin.nodes;
    mixed.labels = lin.labels;
    std::map<std::pair<int, int>, int> mid;
    for (std::size_t t = 0; t < lin.tets.size(); ++t) {
        Tet10 e{};
        for (std::size_t k = 0; k < 4; ++k) e[k] = lin.tets[t][k];
        const bool quadratic = labelKind(lin.labels[t]) == LabelKind::Pdl;
        if (quadratic)
            for (std::size_t k = 0; k < 6; ++k) {
                const int a = e[static_cast<std::size_t>(kGmshTet10Edges[k][0])], b = e[static_cast<std::size_t>(kGmshTet10Edges[k][1])];
                const auto key = std::minmax(a, b);
                auto it = mid.find(key);
                if (it == mid.end()) {
                    mixed.nodes.push_back(0.5 * (lin.nodes[static_cast<std::size_t>(a)] + lin.nodes[static_cast<std::size_t>(b)]));
                    it = mid.emplace(key, static_cast<int>(mixed.nodes.size() - 1)).first;
                }
                e[4 + k] = it->second;
            }
        mixed.tets.push_back(e);
        mixed.quadratic.push_back(quadratic ? 1 : 0);
    }
    for (bool binary : {false, true}) {
        const fs::path path = dir / (binary ? "b.msh" : "a.msh");
        writeGmsh(mixed, path.string(), GmshWriteOptions{binary});
        const TetMesh back = readGmsh(path.string());
        EXPECT_EQ(back.tets, lin.tets);  // corners of Tet10 and Tet4 alike
        EXPECT_EQ(back.labels, lin.labels);
        EXPECT_EQ(back.nodes.size(), mixed.nodes.size());
    }
}

TEST(GmshWriter, RejectsBadInputAndReaderRejectsBadFiles) {
    const auto dir = scratchDir("gmsh-bad");
    TetMesh mesh = smallJaw();
    mesh.labels[0] = 0;
    EXPECT_THROW(writeGmsh(mesh, (dir / "x.msh").string()), Error);
    EXPECT_FALSE(fs::exists(dir / "x.msh"));

    writeGmsh(smallJaw(), (dir / "good.msh").string());
    const std::string text = test::readText(dir / "good.msh");
    std::ofstream((dir / "truncated.msh").string()) << text.substr(0, text.size() / 2);
    EXPECT_THROW(readGmsh((dir / "truncated.msh").string()), Error);
    std::ofstream((dir / "v22.msh").string()) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    EXPECT_THROW(readGmsh((dir / "v22.msh").string()), Error);
    std::ofstream((dir / "noise.msh").string()) << "solid foo\n";
    EXPECT_THROW(readGmsh((dir / "noise.msh").string()), Error);
    EXPECT_THROW(readGmsh((dir / "missing.msh").string()), Error);

    GmshWriteOptions bin;
    bin.binary = true;
    writeGmsh(smallJaw(), (dir / "good_b.msh").string(), bin);
    const std::string b = test::readText(dir / "good_b.msh");
    std::ofstream((dir / "truncated_b.msh").string(), std::ios::binary) << b.substr(0, b.size() - 200);
    EXPECT_THROW(readGmsh((dir / "truncated_b.msh").string()), Error);
}

TEST(VtuWriter, WritesAppendedBinaryWithLabels) {
    const auto dir = scratchDir("vtu");
    const TetMesh mesh = smallJaw();
    writeVtu(mesh, (dir / "m.vtu").string());
    const std::string text = test::readText(dir / "m.vtu");
    EXPECT_NE(text.find("NumberOfPoints=\"" + std::to_string(mesh.nodes.size()) + "\""), std::string::npos);
    EXPECT_NE(text.find("NumberOfCells=\"" + std::to_string(mesh.tets.size()) + "\""), std::string::npos);
    EXPECT_NE(text.find("type=\"Int32\" Name=\"label\""), std::string::npos);
    // Header + 5 arrays with UInt64 size headers.
    const std::size_t payload = 5 * 8 + mesh.nodes.size() * 24 + mesh.tets.size() * (32 + 8 + 1 + 4);
    EXPECT_GT(text.size(), payload);
    EXPECT_LT(text.size(), payload + 2000);
}

TEST(MeditWriter, WritesVerticesTetsAndTriangles) {
    const auto dir = scratchDir("medit");
    const TetMesh mesh = smallJaw();
    MeditTriangles tris;
    tris.triangles.push_back({0, 1, 2});
    tris.references.push_back(1 * 1024 + 124);
    writeMedit(mesh, (dir / "m.mesh").string(), &tris);
    std::ifstream in(dir / "m.mesh");
    std::string word;
    std::map<std::string, long> counts;
    std::map<int, long> refs;
    while (in >> word) {
        if (word == "Vertices" || word == "Tetrahedra" || word == "Triangles") {
            long n;
            in >> n;
            counts[word] = n;
            if (word == "Tetrahedra")
                for (long i = 0; i < n; ++i) {
                    long a, b, c, d;
                    int r;
                    in >> a >> b >> c >> d >> r;
                    ++refs[r];
                    EXPECT_GE(std::min({a, b, c, d}), 1);
                }
        }
    }
    EXPECT_EQ(counts["Vertices"], static_cast<long>(mesh.nodes.size()));
    EXPECT_EQ(counts["Tetrahedra"], static_cast<long>(mesh.tets.size()));
    EXPECT_EQ(counts["Triangles"], 1);
    std::map<int, long> expected;
    for (Label l : mesh.labels) ++expected[l];
    EXPECT_EQ(refs, expected);
}

TEST(LabelsJson, MatchesDesign) {
    const auto dir = scratchDir("labels-json");
    writeLabelsJson({224, 124, 1, 124}, (dir / "labels.json").string());
    const auto j = nlohmann::json::parse(test::readText(dir / "labels.json"));
    const auto expected = nlohmann::json::parse(R"({"labels": {
        "1": {"kind": "bone", "jaw": "mandible", "name": "bone_mandible"},
        "124": {"kind": "tooth", "tooth": 24, "name": "tooth_24"},
        "224": {"kind": "pdl", "tooth": 24, "name": "pdl_24"}}})");
    EXPECT_EQ(j, expected);
    EXPECT_THROW(labelsJson({0}), Error);
    EXPECT_THROW(labelsJson({99}), Error);
}

TEST(VolumeWriters, MeshioReadsMshAndVtu) {
    const std::string py = pythonWithMeshio();
    if (py.empty()) GTEST_SKIP() << "Python meshio not installed (Debian: apt-get install python3-meshio)";
    const auto dir = scratchDir("meshio");
    const TetMesh mesh = smallJaw();
    writeGmsh(mesh, (dir / "a.msh").string());
    GmshWriteOptions bin;
    bin.binary = true;
    writeGmsh(mesh, (dir / "b.msh").string(), bin);
    writeVtu(mesh, (dir / "m.vtu").string());
    std::map<Label, long> perLabel;
    for (Label l : mesh.labels) ++perLabel[l];
    std::string expectedLabels;
    for (const auto& [l, n] : perLabel) expectedLabels += std::to_string(l) + ":" + std::to_string(n) + " ";
    const std::string script =
        "import sys, meshio, collections\n"
        "m = meshio.read(sys.argv[1])\n"
        "tets = sum(len(c.data) for c in m.cells if c.type == 'tetra')\n"
        "key = 'gmsh:physical' if 'gmsh:physical' in m.cell_data else 'label'\n"
        "labels = collections.Counter()\n"
        "for c, d in zip(m.cells, m.cell_data[key]):\n"
        "    labels.update(int(x) for x in d)\n"
        "print(len(m.points), tets, ' '.join(f'{k}:{v}' for k, v in sorted(labels.items())) + ' ')\n";
    std::ofstream((dir / "check.py").string()) << script;
    for (const char* file : {"a.msh", "b.msh", "m.vtu"}) {
        // meshio may print notices first; the answer is the last line.
        std::string out = run(py + " " + (dir / "check.py").string() + " " + (dir / file).string() + " 2>&1");
        const std::size_t lastLine = out.rfind('\n', out.size() >= 2 ? out.size() - 2 : 0);
        if (lastLine != std::string::npos && lastLine + 1 < out.size()) out = out.substr(lastLine + 1);
        const std::string expected = std::to_string(mesh.nodes.size()) + " " + std::to_string(mesh.tets.size()) + " " + expectedLabels + "\n";
        EXPECT_EQ(out, expected) << file;
    }
}
