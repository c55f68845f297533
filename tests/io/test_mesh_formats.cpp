// Readers and writers of every surface format on small generated shapes.
#include "io/MeshIO.h"
#include "support/TestData.h"
#include "io/IoTestUtil.h"

#include <cmath>
#include <cstring>
#include <random>
#include <unistd.h>

namespace jawmesh::test {
namespace {

/// A jittered box with non-representable decimals so that round trips exercise full precision.
SurfaceMesh oddBox() {
    SurfaceMesh m = boxMesh(Vec3(0.1, -2.3, 5.7), Vec3(10.123456789, 3.3, 9.9));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> d(-0.01, 0.01);
    for (Vec3& v : m.vertices) v += Vec3(d(rng), d(rng), d(rng));
    return m;
}

TEST(MeshFormats, RoundTripEveryWritableFormat) {
    const auto dir = scratchDir("io-roundtrip");
    const SurfaceMesh box = oddBox();
    for (const char* ext : {"stl", "ply", "obj", "STL", "Ply"}) {
        const std::string path = (dir / (std::string("box.") + ext)).string();
        writeSurface(box, path);
        const SurfaceMesh back = readSurface(path);
        // STL stores floats; PLY (double) and OBJ (shortest round-trip decimals) are exact.
        const bool isStl = surfaceExtension(path) == "stl";
        EXPECT_TRUE(sameGeometry(box, back, isStl ? 1e-5 : 0.0)) << path;
        EXPECT_EQ(back.vertices.size(), box.vertices.size()) << path << ": STL welding should recover 8 corners";
        EXPECT_NEAR(signedVolume(back), signedVolume(box), 1e-3) << path;
        EXPECT_FALSE(std::filesystem::exists(path + ".tmp-" + std::to_string(::getpid())));
    }
}

TEST(MeshFormats, WriteRejectsUnknownExtensionAndBadIndices) {
    const auto dir = scratchDir("io-write-errors");
    const SurfaceMesh box = boxMesh(Vec3::Zero(), Vec3::Ones());
    expectErrorNaming([&] { writeSurface(box, (dir / "a.vtk").string()); }, "a.vtk", ".vtk");
    SurfaceMesh broken = box;
    broken.triangles[3][1] = 99;
    expectErrorNaming([&] { writeSurface(broken, (dir / "b.stl").string()); }, "b.stl");
    EXPECT_FALSE(std::filesystem::exists(dir / "b.stl"));
}

std::string asciiStl(const SurfaceMesh& m, const std::string& name) {
    std::string s = "solid " + name + "\n";
    for (const Tri& t : m.triangles) {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for (int v : t) {
            const Vec3& p = m.vertices[static_cast<std::size_t>(v)];
            s += "      vertex " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " +" + std::to_string(p.z()) + "\n";
        }
        s += "    endloop\n  endfacet\n";
    }
    return s + "endsolid " + name + "\r\n";
}

TEST(MeshFormats, AsciiStlIsReadAndWelded) {
    const auto dir = scratchDir("io-ascii-stl");
    const SurfaceMesh box = boxMesh(Vec3(1, 2, 3), Vec3(4, 5.5, 6));
    writeBytes(dir / "box.stl", asciiStl(box, "my part"));
    const SurfaceMesh back = readSurface((dir / "box.stl").string());
    EXPECT_EQ(back.vertices.size(), 8u);
    EXPECT_TRUE(sameGeometry(box, back, 1e-6));
}

TEST(MeshFormats, BinaryStlWhoseHeaderStartsWithSolidIsBinary) {
    const auto dir = scratchDir("io-solid-binary");
    const SurfaceMesh box = boxMesh(Vec3(0, 0, 0), Vec3(1, 2, 3));
    writeSurface(box, (dir / "box.stl").string());
    std::string bytes = readBytes(dir / "box.stl");
    std::memcpy(bytes.data(), "solid exported by VTK", 21);
    writeBytes(dir / "solid.stl", bytes);
    EXPECT_TRUE(sameGeometry(box, readSurface((dir / "solid.stl").string()), 1e-6));
}

TEST(MeshFormats, StlWeldsMinusZeroAndKeepsDistinctPoints) {
    const auto dir = scratchDir("io-weld");
    SurfaceMesh soup;
    soup.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-0.0, 0, -0.0), Vec3(0, 1, 0), Vec3(0, 0, 1),
                     Vec3(1e-7, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)};
    soup.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
    writeSurface(soup, (dir / "soup.stl").string());
    const SurfaceMesh m = readSurface((dir / "soup.stl").string());
    ASSERT_EQ(m.triangles.size(), 3u);
    EXPECT_EQ(m.vertices.size(), 5u);  // 0, (1,0,0), (0,1,0), (0,0,1), (1e-7,0,0)
    EXPECT_EQ(m.triangles[1][0], m.triangles[0][0]);
    EXPECT_EQ(m.triangles[1][1], m.triangles[0][2]);
    EXPECT_NE(m.triangles[2][0], m.triangles[0][0]);
    EXPECT_EQ(m.triangles[2][1], m.triangles[0][1]);
    // First-use order: vertex ids grow along the corners.
    EXPECT_EQ(m.triangles[0], (Tri{0, 1, 2}));
}

TEST(MeshFormats, LargeStlWeldingMatchesAGrid) {
    // A regular grid surface written as a soup: enough corners for many weld buckets and chunks.
    const int n = 300;
    SurfaceMesh grid;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) grid.vertices.emplace_back(0.37 * i, 0.29 * j, 0.01 * ((i * j) % 7));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i;
            grid.triangles.push_back({a, a + 1, a + n + 2});
            grid.triangles.push_back({a, a + n + 2, a + n + 1});
        }
    const auto dir = scratchDir("io-weld-grid");
    writeSurface(grid, (dir / "grid.stl").string());
    const SurfaceMesh m = readSurface((dir / "grid.stl").string());
    EXPECT_EQ(m.vertices.size(), grid.vertices.size());
    EXPECT_TRUE(sameGeometry(grid, m, 1e-4));
    // Vertex numbering is in order of first use.
    std::int32_t seen = -1;
    for (const Tri& t : m.triangles)
        for (std::int32_t v : t) {
            EXPECT_LE(v, seen + 1);
            seen = std::max(seen, v);
        }
}

TEST(MeshFormats, ObjCornerFormsNegativeIndicesAndPolygons) {
    const auto dir = scratchDir("io-obj");
    writeBytes(dir / "q.obj",
               "# comment\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0 0.5 0.5 0.5\n"
               "vt 0 0\nvn 0 0 1\ng g1\nusemtl m\ns off\n"
               "f 1/1/1 2/1/1 3/1/1 4/1/1\n"   // quad -> 2 triangles
               "f -4//1 -3//1 -2//1\n"          // relative: 1 2 3
               "f 1/1 3/1 4/1\n"
               "v 0 0 1\n"
               "f -5 -4 -1\r\n"                 // relative after a 5th vertex: 1 2 5
               "l 1 2\n");
    const SurfaceMesh m = readSurface((dir / "q.obj").string());
    ASSERT_EQ(m.vertices.size(), 5u);
    ASSERT_EQ(m.triangles.size(), 5u);
    EXPECT_EQ(m.triangles[0], (Tri{0, 1, 2}));
    EXPECT_EQ(m.triangles[1], (Tri{0, 2, 3}));
    EXPECT_EQ(m.triangles[2], (Tri{0, 1, 2}));
    EXPECT_EQ(m.triangles[3], (Tri{0, 2, 3}));
    EXPECT_EQ(m.triangles[4], (Tri{0, 1, 4}));
    EXPECT_EQ(m.vertices[4], Vec3(0, 0, 1));
}

TEST(MeshFormats, PlyAsciiWithExtraPropertiesAnyOrderAndOtherElements) {
    const auto dir = scratchDir("io-ply-ascii");
    writeBytes(dir / "a.ply",
               "ply\nformat ascii 1.0\ncomment made by hand\nobj_info x\n"
               "element vertex 4\nproperty uchar red\nproperty double z\nproperty float confidence\n"
               "property list uchar float weights\nproperty double x\nproperty double y\n"
               "element material 1\nproperty float shininess\n"
               "element face 2\nproperty int flags\nproperty list uint8 uint32 vertex_index\n"
               "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
               "255 0.5 nan 2 1 2 0 0\n 0 0.5 1 0 1 0\n0 0.5 1 1 3 1 1\n0 0.5 1 0 0 1\n"
               "0.7\n"
               "7 4 0 1 2 3\n8 3 0 2 3\n"
               "0 1\n");
    const SurfaceMesh m = readSurface((dir / "a.ply").string());
    ASSERT_EQ(m.vertices.size(), 4u);
    EXPECT_EQ(m.vertices[0], Vec3(0, 0, 0.5));
    EXPECT_EQ(m.vertices[2], Vec3(1, 1, 0.5));
    ASSERT_EQ(m.triangles.size(), 3u);
    EXPECT_EQ(m.triangles[1], (Tri{0, 2, 3}));
    EXPECT_EQ(m.triangles[2], (Tri{0, 2, 3}));
}

TEST(MeshFormats, PlyBinaryWithFloatCoordinatesAndShortIndices) {
    std::string body;
    auto put = [&](const auto& v) { body.append(reinterpret_cast<const char*>(&v), sizeof v); };
    const float xyz[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {0, 0, 4}};
    for (int i = 0; i < 4; ++i) {
        put(std::int16_t(-5));  // an extra property before x
        put(xyz[i][0]);
        put(xyz[i][1]);
        put(double(99));
        put(xyz[i][2]);
    }
    const std::uint16_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (auto& f : faces) {
        put(std::uint32_t(3));
        for (std::uint16_t i : f) put(i);
        put(std::uint8_t(1));
        put(std::int32_t(42));
    }
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty short s\nproperty float x\nproperty float y\n"
        "property double extra\nproperty float z\nelement face 4\nproperty list uint ushort vertex_indices\n"
        "property list uchar int tags\nend_header\n";
    const auto dir = scratchDir("io-ply-binary");
    writeBytes(dir / "t.ply", header + body);
    const SurfaceMesh m = readSurface((dir / "t.ply").string());
    ASSERT_EQ(m.vertices.size(), 4u);
    EXPECT_EQ(m.vertices[3], Vec3(0, 0, 4));
    ASSERT_EQ(m.triangles.size(), 4u);
    EXPECT_NEAR(signedVolume(m), 2.0 * 3.0 * 4.0 / 6.0, 1e-12);
}

TEST(MeshFormats, OffWithCommentsCountsOnHeaderLineAndPolygons) {
    const auto dir = scratchDir("io-off");
    writeBytes(dir / "a.off", "# leading comment\nOFF\n\n4 2 0 # counts\n0 0 0\n1 0 0\n# mid comment\n1 1 0\n0 1 0\n4 0 1 2 3\n3 0 2 3 255 0 0\n");
    SurfaceMesh m = readSurface((dir / "a.off").string());
    EXPECT_EQ(m.vertices.size(), 4u);
    ASSERT_EQ(m.triangles.size(), 3u);
    EXPECT_EQ(m.triangles[1], (Tri{0, 2, 3}));
    writeBytes(dir / "b.OFF", "COFF 3 1 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n");
    m = readSurface((dir / "b.OFF").string());
    EXPECT_EQ(m.triangles.size(), 1u);
    EXPECT_EQ(m.vertices[1], Vec3(1, 0, 0));
}

}  // namespace
}  // namespace jawmesh::test
