// TetGen .poly / .smesh output of an extracted interface complex, and per-region boundaries.
#include "filters/ExtractInterfaces.h"
#include "io/MeshIO.h"
#include "io/PolyWriter.h"
#include "support/TestData.h"
#include "support_SyntheticLabels.h"
#include "tet/Tetrahedralize.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace jawmesh {
namespace {

std::vector<std::string> dataLines(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line[0] != '#') lines.push_back(line);
    return lines;
}

TEST(PolyWriter, PolyAndSmeshMatchTheComplex) {
    const auto syn = test::jawPhantom(0.1);
    const InterfaceComplex c = extractInterfaces(syn.field);
    const auto dir = test::scratchDir("poly-writer");
    for (const std::string ext : {".poly", ".smesh"}) {
        const std::string path = (dir / ("jaw" + ext)).string();
        writeTetgenPoly(c, path);
        const auto lines = dataLines(path);
        std::size_t at = 0;
        std::istringstream head(lines[at++]);
        std::size_t nv = 0;
        head >> nv;
        EXPECT_EQ(nv, c.surface.vertices.size());
        at += nv;
        std::istringstream fh(lines[at++]);
        std::size_t nf = 0;
        fh >> nf;
        ASSERT_EQ(nf, c.surface.triangles.size());
        for (std::size_t t = 0; t < nf; ++t) {
            int marker = 0;
            if (ext == ".poly") {
                std::istringstream f(lines[at++]);
                int polys, holes;
                f >> polys >> holes >> marker;
                ++at;
            } else {
                std::istringstream f(lines[at++]);
                int n, a, b, d;
                f >> n >> a >> b >> d >> marker;
            }
            ASSERT_EQ(interfacePairFromMarker(marker), c.sides[t]);
        }
        EXPECT_EQ(lines[at++], "0");
        std::size_t nr = 0;
        std::istringstream(lines[at++]) >> nr;
        EXPECT_EQ(nr, c.seeds.size());
        for (std::size_t r = 0; r < nr; ++r) {
            std::istringstream f(lines[at++]);
            int idx;
            double x, y, z;
            Label label;
            f >> idx >> x >> y >> z >> label;
            EXPECT_EQ(label, c.seeds[r].label);
            EXPECT_DOUBLE_EQ(x, c.seeds[r].point.x());
        }
    }
    writeRegionBoundaries(c, dir.string());
    const SurfaceMesh bone = readSurface((dir / "bone_mandible.ply").string());
    EXPECT_EQ(bone.triangles.size(), regionBoundary(c, kMandibleBoneLabel).triangles.size());
    EXPECT_GT(signedVolume(bone), 0.0);  // oriented outward
}

}  // namespace
}  // namespace jawmesh
