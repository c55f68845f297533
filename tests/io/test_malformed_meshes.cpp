// Malformed surface files: each must give jawmesh::Error naming the file, never a crash, a hang or
// a huge allocation; random bytes must only ever throw Error or read.
#include "io/MeshIO.h"
#include "support/TestData.h"
#include "io/IoTestUtil.h"

#include <cstring>
#include <random>

namespace jawmesh::test {
namespace {

struct Case {
    const char* name;      ///< file name (extension picks the reader)
    std::string bytes;
    const char* fragment;  ///< expected in the message
};

std::string binaryStlHeader(std::uint32_t count) {
    std::string s(80, ' ');
    s.append(reinterpret_cast<const char*>(&count), 4);
    return s;
}

std::string binaryStlTriangle(float a, float b, float c) {
    const float v[12] = {0, 0, 1, a, 0, 0, 1, b, 0, 0, 1, c};
    std::string s(reinterpret_cast<const char*>(v), 48);
    return s + std::string(2, '\0');
}

std::vector<Case> malformedCases() {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::string plyHead = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const std::string goodAsciiStl = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
    return {
        {"empty.stl", "", "empty"},
        {"empty.obj", "", "empty"},
        {"empty.ply", "", "empty"},
        {"empty.off", "", "empty"},
        {"short.stl", "abc", "84-byte"},
        {"truncated.stl", binaryStlHeader(3) + binaryStlTriangle(0, 1, 2), "promises 3 triangles"},
        {"absurd.stl", binaryStlHeader(0xffffffffu) + binaryStlTriangle(0, 1, 2), "promises 4294967295"},
        {"zero.stl", binaryStlHeader(0), "no triangles"},
        {"nan.stl", binaryStlHeader(1) + binaryStlTriangle(0, nan, 2), "NaN"},
        {"inf.stl", binaryStlHeader(1) + binaryStlTriangle(inf, 1, 2), "NaN or infinite"},
        {"ascii_truncated.stl", goodAsciiStl.substr(0, goodAsciiStl.find("endloop")), "truncated"},
        {"ascii_nan.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\n", "not a finite number"},
        {"ascii_four.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 0\n", "more than 3"},
        {"ascii_junk.stl", "solid s\nhello\n", "unexpected"},
        {"ascii_big.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 1e39 0 0\n", "not a finite"},
        {"noverts.obj", "# nothing\ng x\n", "no triangles"},
        {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "outside"},
        {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "not a valid vertex"},
        {"negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "reaches before"},
        {"nan.obj", "v 0 nan 0\n", "not a finite number"},
        {"inf.obj", "v 0 inf 0\n", "not a finite number"},
        {"short.obj", "v 0 0\n", "not a finite number"},
        {"twocorner.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "at least 3"},
        {"binary.obj", std::string("v 0 0 0\n\0\x01\x02", 11), "binary"},
        {"noply.ply", "plx\n", "not a PLY"},
        {"bigendian.ply", "ply\nformat binary_big_endian 1.0\nend_header\n", "big_endian"},
        {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", "end_header"},
        {"ply_truncated.ply", plyHead + "0 0 0\n1 0 0\n", "truncated"},
        {"ply_absurd.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n" + std::string(12, '\0'), "promises 1000000000000"},
        {"ply_range.ply", plyHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "outside"},
        {"ply_negative.ply", plyHead + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "out of range"},
        {"ply_nan.ply", plyHead + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "not a finite"},
        {"ply_noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n", "x, y, z"},
        {"ply_noface.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n", "no face"},
        {"ply_hugelist.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n" + std::string(36, '\0') + std::string("\xff\xff\xff\x7f", 4) + std::string(12, '\0'), "longer than the rest"},
        {"ply_nanbinary.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n" + std::string("\0\0\xc0\x7f", 4) + std::string(8, '\0'), "NaN"},
        {"noheader.off", "4 2 0\n", "OFF"},
        {"truncated.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n", "promises"},
        {"truncated2.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n", "truncated"},
        {"absurd.off", "OFF\n1000000000000 1 0\n0 0 0\n", "promises"},
        {"range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "outside"},
        {"negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "outside"},
        {"nan.off", "OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n", "not a finite"},
        {"shortface.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "not an integer"},
        {"unknown.vtk", "whatever", "unsupported"},
    };
}

TEST(MalformedMeshes, EveryCaseThrowsErrorNamingTheFile) {
    const auto dir = scratchDir("io-malformed");
    for (const Case& c : malformedCases()) {
        const std::string path = (dir / c.name).string();
        writeBytes(path, c.bytes);
        SCOPED_TRACE(c.name);
        expectErrorNaming([&] { readSurface(path); }, path, c.fragment);
    }
}

TEST(MalformedMeshes, MissingFileNamesTheFile) {
    const std::string path = (scratchDir("io-missing") / "nope.stl").string();
    expectErrorNaming([&] { readSurface(path); }, path, "cannot open");
    const auto folder = scratchDir("io-folder") / "looks_like.stl";
    std::filesystem::create_directories(folder);
    expectErrorNaming([&] { readSurface(folder.string()); }, folder.string(), "not a regular file");
}

/// Mutates valid files of each format (flips, truncation, random insertion) and also feeds pure
/// noise: every read either succeeds with a valid mesh or throws Error.
TEST(MalformedMeshes, RandomBytesOnlyEverThrowError) {
    const auto dir = scratchDir("io-fuzz");
    const SurfaceMesh box = boxMesh(Vec3(0, 0, 0), Vec3(1, 2, 3));
    std::vector<std::pair<std::string, std::string>> seeds;  // extension, valid bytes
    for (const char* ext : {"stl", "ply", "obj"}) {
        const auto p = dir / (std::string("seed.") + ext);
        writeSurface(box, p.string());
        seeds.emplace_back(ext, readBytes(p));
    }
    seeds.emplace_back("off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n3 0 2 3\n");
    seeds.emplace_back("ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                              "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    seeds.emplace_back("stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n");
    std::mt19937 rng(12345);
    int reads = 0, accepted = 0;
    static const char kAlphabet[] = "0123456789 -+.e\nvf/#plyOFsoidnatxz\0\xff";
    const std::string alphabet(kAlphabet, sizeof kAlphabet - 1);
    for (const auto& [ext, valid] : seeds) {
        for (int round = 0; round < 1500; ++round) {
            std::string bytes = valid;
            const int kind = round % 4;
            if (kind == 0) {  // pure noise
                bytes.resize(rng() % 300);
                for (char& c : bytes) c = static_cast<char>(rng());
            } else if (kind == 1) {  // truncate
                bytes.resize(rng() % (bytes.size() + 1));
            } else {  // flip or insert a few bytes, sometimes from a format-like alphabet
                const int edits = 1 + static_cast<int>(rng() % 4);
                for (int e = 0; e < edits && !bytes.empty(); ++e) {
                    const std::size_t at = rng() % bytes.size();
                    const char c = kind == 2 ? static_cast<char>(rng()) : alphabet[rng() % alphabet.size()];
                    if (rng() % 2) bytes[at] = c;
                    else bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), c);
                }
            }
            // In memory (the file system is slow here); readSurface() parses files the same way.
            const std::string path = "fuzz-" + std::to_string(round) + "." + ext;
            ++reads;
            try {
                const SurfaceMesh m = readSurfaceFromMemory(bytes, path);
                ++accepted;
                ASSERT_FALSE(m.triangles.empty());
                for (const Tri& t : m.triangles)
                    for (std::int32_t v : t) ASSERT_TRUE(v >= 0 && static_cast<std::size_t>(v) < m.vertices.size());
                for (const Vec3& v : m.vertices) ASSERT_TRUE(v.allFinite());
            } catch (const Error& e) {
                ASSERT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
            }
        }
    }
    EXPECT_EQ(reads, 9000);
    EXPECT_GT(accepted, 0);  // some mutations keep a valid file: the loop really reads
}

}  // namespace
}  // namespace jawmesh::test
