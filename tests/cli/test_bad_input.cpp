// Bad input end to end (issue #9): a light two-tooth phantom spoiled one way at a time. Input that
// cannot give a correct mesh must stop `jawmesh run` with exit code 1 and one error line naming the
// file and the problem, leaving nothing in the output folder (no file, no staging folder, no
// temporary file). Dirty but usable input (holes, a triangle soup, flipped and duplicated faces,
// self-intersections, teeth in contact) must mesh and validate. Reader-level cases are in
// tests/io/test_malformed_meshes.cpp; level-set repairs on real anatomy in tests/levelset/slow_*.
#include "io/IoTestUtil.h"
#include "io/MeshIO.h"
#include "support/TestData.h"
#include "support_CliRun.h"
#include "support_RunChecks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

namespace jawmesh::test {
namespace {
namespace fs = std::filesystem;

class BadInput : public ::testing::Test {
protected:
    /// The clean phantom case (written once per test process): mandible, teeth 24 and 25.
    static const fs::path& base() {
        static const fs::path dir = [] {
            const fs::path d = processScratchDir("bad-input-base") / "case";
            const CliResult r = runJawmesh("-q phantom " + d.string() + " --teeth 2 --seed 1 --triangles-scale 0.3",
                                           d.parent_path() / "phantom.log");
            EXPECT_EQ(r.exitCode, 0) << r.output;
            return d;
        }();
        return dir;
    }
    static fs::path jawDir(const fs::path& caseDir) { return caseDir / "input" / "mandible"; }
    static fs::path tooth(const fs::path& caseDir, int unn) {
        return jawDir(caseDir) / "teeth" / ("tooth_" + std::to_string(unn) + ".stl");
    }
    static fs::path bone(const fs::path& caseDir) { return jawDir(caseDir) / "bone" / "mandible.stl"; }

    /// A copy of the clean case under scratch/<name>/case, changed by spoil(case folder).
    static fs::path spoiled(const std::string& name, const std::function<void(const fs::path&)>& spoil) {
        const fs::path caseDir = scratchDir("bad-input-" + name) / "case";
        fs::copy(base(), caseDir, fs::copy_options::recursive);
        spoil(caseDir);
        return caseDir;
    }

    /// `jawmesh run` must refuse the case: exit code 1, one "jawmesh: error:" line holding both
    /// fragments, and nothing beside the case folder but the log.
    static void expectRefused(const fs::path& caseDir, const std::string& file, const std::string& problem,
                              const std::string& extraArgs = "", const std::string& config = fastConfig()) {
        const fs::path root = caseDir.parent_path(), out = root / "out";
        const CliResult r = runJawmesh("-q run " + caseDir.string() + " -o " + out.string() + " --config " + config +
                                           " " + extraArgs,
                                       root / "run.log");
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_EQ(r.output.rfind("jawmesh: error: ", 0), 0u) << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line expected: " << r.output;
        EXPECT_NE(r.output.find(file), std::string::npos) << "expected the file '" << file << "' in: " << r.output;
        EXPECT_NE(r.output.find(problem), std::string::npos) << "expected '" << problem << "' in: " << r.output;
        EXPECT_TRUE(filesUnder(out).empty()) << out;
        EXPECT_FALSE(fs::exists(out)) << "an output folder was left: " << out;
        EXPECT_TRUE(leftoversUnder(root).empty()) << leftoversUnder(root).front();
    }
};

std::uint32_t stlCount(const std::string& bytes) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    return count;
}

/// A surface as ASCII PLY text (the writers only write binary PLY).
std::string asciiPly(const SurfaceMesh& m) {
    std::ostringstream s;
    s << "ply\nformat ascii 1.0\nelement vertex " << m.vertices.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
    for (const Vec3& v : m.vertices) s << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const Tri& t : m.triangles) s << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
    return s.str();
}

/// Replaces the tooth's STL by `text` under another extension.
void replaceTooth(const fs::path& stl, const std::string& extension, const std::string& text) {
    fs::remove(stl);
    writeBytes(fs::path(stl).replace_extension(extension), text);
}

SurfaceMesh moved(SurfaceMesh m, const Vec3& by) {
    for (Vec3& v : m.vertices) v += by;
    return m;
}

TEST_F(BadInput, EmptyStl) {
    const fs::path c = spoiled("empty", [](const fs::path& c) { writeBytes(bone(c), ""); });
    expectRefused(c, "bone/mandible.stl", "file is empty");
}

TEST_F(BadInput, TruncatedStl) {
    const fs::path c = spoiled("truncated", [](const fs::path& c) {
        const std::string bytes = readBytes(tooth(c, 24));
        writeBytes(tooth(c, 24), bytes.substr(0, bytes.size() / 2 + 7));
    });
    expectRefused(c, "tooth_24.stl", "truncated");
}

TEST_F(BadInput, StlHeaderPromisingMoreTriangles) {
    const fs::path c = spoiled("lying-more", [](const fs::path& c) {
        std::string bytes = readBytes(tooth(c, 25));
        const std::uint32_t lie = stlCount(bytes) + 1000;
        std::memcpy(bytes.data() + 80, &lie, 4);
        writeBytes(tooth(c, 25), bytes);
    });
    expectRefused(c, "tooth_25.stl", "promises");
}

TEST_F(BadInput, StlHeaderPromisingFewerTriangles) {
    const fs::path c = spoiled("lying-fewer", [](const fs::path& c) {
        std::string bytes = readBytes(bone(c));
        const std::uint32_t lie = stlCount(bytes) / 2;
        std::memcpy(bytes.data() + 80, &lie, 4);
        writeBytes(bone(c), bytes);
    });
    expectRefused(c, "mandible.stl", "corrupt or not an STL file");
}

TEST_F(BadInput, NanCoordinateInBinaryStl) {
    const fs::path c = spoiled("nan", [](const fs::path& c) {
        std::string bytes = readBytes(tooth(c, 24));
        const float nan = std::numeric_limits<float>::quiet_NaN();
        std::memcpy(bytes.data() + 84 + 50 * 7 + 16, &nan, 4);  // triangle 7, first corner, y
        writeBytes(tooth(c, 24), bytes);
    });
    expectRefused(c, "tooth_24.stl", "NaN");
}

TEST_F(BadInput, InfiniteCoordinateInObj) {
    const fs::path c = spoiled("inf", [](const fs::path& c) {
        SurfaceMesh m = readSurface(tooth(c, 25).string());
        m.vertices[3].z() = std::numeric_limits<double>::infinity();
        std::ostringstream s;
        for (const Vec3& v : m.vertices) s << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
        for (const Tri& t : m.triangles) s << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
        replaceTooth(tooth(c, 25), ".obj", s.str());
    });
    expectRefused(c, "tooth_25.obj", "not a finite number");
}

TEST_F(BadInput, PlyIndexOutOfRange) {
    const fs::path c = spoiled("ply-range", [](const fs::path& c) {
        SurfaceMesh m = readSurface(tooth(c, 24).string());
        m.triangles[5][1] = static_cast<std::int32_t>(m.vertices.size() + 3);
        replaceTooth(tooth(c, 24), ".ply", asciiPly(m));
    });
    expectRefused(c, "tooth_24.ply", "outside");
}

TEST_F(BadInput, PlyNegativeIndex) {
    const fs::path c = spoiled("ply-negative", [](const fs::path& c) {
        SurfaceMesh m = readSurface(tooth(c, 24).string());
        m.triangles[2][0] = -4;
        replaceTooth(tooth(c, 24), ".ply", asciiPly(m));
    });
    expectRefused(c, "tooth_24.ply", "out of range");
}

TEST_F(BadInput, ObjIndicesOutOfRangeAndBeforeTheFirstVertex) {
    const fs::path high = spoiled("obj-range", [](const fs::path& c) {
        replaceTooth(tooth(c, 25), ".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    });
    expectRefused(high, "tooth_25.obj", "outside 0..2");
    const fs::path negative = spoiled("obj-negative", [](const fs::path& c) {
        replaceTooth(tooth(c, 25), ".obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n");
    });
    expectRefused(negative, "tooth_25.obj", "reaches before the first vertex");
}

TEST_F(BadInput, CaseInMetres) {
    const fs::path c = spoiled("metres", [](const fs::path& c) {
        for (const fs::path& p : {bone(c), tooth(c, 24), tooth(c, 25)}) {
            SurfaceMesh m = readSurface(p.string());
            for (Vec3& v : m.vertices) v *= 0.001;
            writeSurface(m, p.string());
        }
    });
    expectRefused(c, "mandible.stl", "look like metres (pass scale 1000)");
}

TEST_F(BadInput, NoBoneFile) {
    const fs::path c = spoiled("no-bone", [](const fs::path& c) { fs::remove_all(jawDir(c) / "bone"); });
    expectRefused(c, "mandible", "no bone surface");
}

TEST_F(BadInput, NoTeeth) {
    const fs::path c = spoiled("no-teeth", [](const fs::path& c) { fs::remove_all(jawDir(c) / "teeth"); });
    expectRefused(c, "mandible", "no teeth");
}

TEST_F(BadInput, DuplicateUnn) {
    const fs::path c = spoiled("duplicate-unn", [](const fs::path& c) {
        writeSurface(readSurface(tooth(c, 24).string()), (jawDir(c) / "teeth" / "tooth_24.obj").string());
    });
    expectRefused(c, "tooth_24", "is given twice");
}

TEST_F(BadInput, ToothThatIsAPointCloud) {
    const fs::path ply = spoiled("point-cloud-ply", [](const fs::path& c) {
        const SurfaceMesh m = readSurface(tooth(c, 24).string());
        std::ostringstream s;
        s << "ply\nformat ascii 1.0\nelement vertex " << m.vertices.size()
          << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        for (const Vec3& v : m.vertices) s << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
        replaceTooth(tooth(c, 24), ".ply", s.str());
    });
    expectRefused(ply, "tooth_24.ply", "point cloud");
    const fs::path obj = spoiled("point-cloud-obj", [](const fs::path& c) {
        std::ostringstream s;
        for (const Vec3& v : readSurface(tooth(c, 25).string()).vertices) s << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
        replaceTooth(tooth(c, 25), ".obj", s.str());
    });
    expectRefused(obj, "tooth_25.obj", "no triangles");
    // Points exported as zero-area triangles (one per point): read, but no surface to mesh.
    const fs::path degenerate = spoiled("point-cloud-stl", [](const fs::path& c) {
        SurfaceMesh m = readSurface(tooth(c, 24).string());
        m.triangles.clear();
        for (std::size_t i = 0; i < m.vertices.size(); ++i) {
            const auto v = static_cast<std::int32_t>(i);
            m.triangles.push_back({v, v, v});
        }
        writeSurface(m, tooth(c, 24).string());
    });
    expectRefused(degenerate, "tooth_24.stl", "degenerate");
}

TEST_F(BadInput, ToothFarFromAnyBone) {
    const fs::path c = spoiled("far-tooth", [](const fs::path& c) {
        writeSurface(moved(readSurface(tooth(c, 25).string()), Vec3(0, 0, 40)), tooth(c, 25).string());
    });
    expectRefused(c, "tooth_25.stl", "does not reach the bone");
}

TEST_F(BadInput, TwoTeethOverlappingHeavily) {
    const fs::path c = spoiled("overlap", [](const fs::path& c) {
        const SurfaceMesh a = readSurface(tooth(c, 24).string()), b = readSurface(tooth(c, 25).string());
        // Tooth 25 replaced by tooth 24 nudged 0.5 mm toward it: most of the volume is shared.
        const Vec3 toward = (boundingBox(b).min + boundingBox(b).max - boundingBox(a).min - boundingBox(a).max).normalized();
        writeSurface(moved(a, 0.5 * toward), tooth(c, 25).string());
    });
    expectRefused(c, "tooth_25.stl", "overlaps");
}

TEST_F(BadInput, OutOfRangeConfigValue) {
    const fs::path c = spoiled("config", [](const fs::path&) {});
    const fs::path config = c.parent_path() / "zero_voxel.json";
    writeBytes(config, R"({"voxel_mm": 0.0})");
    expectRefused(c, "zero_voxel.json", "'voxel_mm' is 0", "", config.string());
}

TEST_F(BadInput, VoxelNeedingMoreMemoryThanAvailable) {
    const fs::path c = spoiled("memory", [](const fs::path&) {});
    expectRefused(c, "input/mandible", "of memory are available; a voxel of", "--voxel 0.0005");
}

/// Dirty surfaces a segmentation export really gives, all in one case: the bone as a triangle soup
/// (no shared vertices) with holes, tooth 24 with flipped orientation and duplicated faces, tooth 25
/// self-intersecting (two overlapping shells) and moved 0.2 mm into tooth 24. The run must
/// succeed and give a valid mesh as close to the surfaces as the same case without the dirt.
TEST_F(BadInput, DirtySurfacesAreMeshed) {
    const fs::path c = spoiled("dirty", [](const fs::path& c) {
        SurfaceMesh b = readSurface(bone(c).string());
        SurfaceMesh soup;
        for (std::size_t t = 0; t < b.triangles.size(); ++t) {
            if (t % 997 == 0) continue;  // a hole of one triangle every 997 (edges ~0.5 mm: a voxel or two)
            const auto n = static_cast<std::int32_t>(soup.vertices.size());
            for (std::int32_t v : b.triangles[t]) soup.vertices.push_back(b.vertices[static_cast<std::size_t>(v)]);
            soup.triangles.push_back({n, n + 1, n + 2});
        }
        fs::remove(bone(c));
        writeSurface(soup, (jawDir(c) / "bone" / "mandible.obj").string());

        SurfaceMesh t24 = readSurface(tooth(c, 24).string());
        for (Tri& t : t24.triangles) std::swap(t[1], t[2]);
        const std::size_t n = t24.triangles.size();
        for (std::size_t t = 0; t < n; t += 3) t24.triangles.push_back(t24.triangles[t]);
        fs::remove(tooth(c, 24));
        writeSurface(t24, (jawDir(c) / "teeth" / "tooth_24.ply").string());

        // Tooth 25 into contact: moved along the line of the closest vertices until 0.2 mm deep in 24.
        const SurfaceMesh clean24 = readSurface(tooth(base(), 24).string());
        SurfaceMesh t25 = readSurface(tooth(c, 25).string());
        Vec3 from = Vec3::Zero(), to = Vec3::Zero();
        double gap = std::numeric_limits<double>::infinity();
        for (const Vec3& p : t25.vertices)
            for (const Vec3& q : clean24.vertices)
                if ((p - q).squaredNorm() < gap * gap) {
                    gap = (p - q).norm();
                    from = p;
                    to = q;
                }
        t25 = moved(t25, (to - from).normalized() * (gap + 0.2));
        // What the mesh is measured against: the clean surfaces, tooth 25 where it now is.
        const fs::path reference = jawDir(c.parent_path() / "reference");
        fs::create_directories(reference / "teeth");
        fs::copy(jawDir(base()) / "bone", reference / "bone", fs::copy_options::recursive);
        fs::copy(tooth(base(), 24), reference / "teeth" / "tooth_24.stl");
        writeSurface(t25, (reference / "teeth" / "tooth_25.stl").string());
        append(t25, moved(t25, Vec3(0.1, 0.05, 0.1)));
        fs::remove(tooth(c, 25));
        writeSurface(t25, (jawDir(c) / "teeth" / "tooth_25.obj").string());
    });
    // The same case clean, for what the mesh achieves at these coarse options (voxel 0.2 mm; the
    // 0.8 mm PDL moves root and socket surfaces by 0.4 mm).
    const fs::path cleanCase = spoiled("dirty-clean", [&](const fs::path& clean) {
        writeSurface(readSurface((jawDir(c.parent_path() / "reference") / "teeth" / "tooth_25.stl").string()),
                     tooth(clean, 25).string());
    });
    std::map<std::string, RunFigures> figures;
    for (const fs::path& run : {c, cleanCase}) {
        const fs::path out = run.parent_path() / "out";
        const CliResult r = runJawmesh("-q run " + run.string() + " -o " + out.string() + " --config " + fastConfig(),
                                       run.parent_path() / "run.log");
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_TRUE(leftoversUnder(run.parent_path()).empty());
        figures[run == c ? "dirty" : "clean"] =
            measureRun((out / "mandible").string(), jawDir(c.parent_path() / "reference").string(), "mandible", {24, 25});
    }
    const RunFigures& f = figures.at("dirty");
    const RunFigures& clean = figures.at("clean");
    EXPECT_TRUE(f.validation.valid()) << (f.validation.messages.empty() ? "" : f.validation.messages.front());
    EXPECT_TRUE(f.validation.missingTeeth.empty() && f.validation.missingPdls.empty());
    EXPECT_EQ(f.validation.teethSharingNodes, 0u);
    for (int unn : {24, 25}) {
        std::printf("tooth %d: Hausdorff %.3f mm (clean %.3f), PDL %.3f mm (clean %.3f)\n", unn, f.toothHausdorffMm.at(unn),
                    clean.toothHausdorffMm.at(unn), f.pdlThicknessMeanMm.at(unn), clean.pdlThicknessMeanMm.at(unn));
        // Within 1.5 voxels of the clean result: tooth 25's second shell lies 0.15 mm out, and the
        // contact with tooth 24 is split between the two.
        EXPECT_LE(f.toothHausdorffMm.at(unn), clean.toothHausdorffMm.at(unn) + 0.3) << "tooth " << unn;
        EXPECT_NEAR(f.pdlThicknessMeanMm.at(unn), clean.pdlThicknessMeanMm.at(unn), 0.1) << "tooth " << unn;
    }
    std::printf("bone: Hausdorff %.3f mm (clean %.3f)\n", f.boneHausdorffMm, clean.boneHausdorffMm);
    EXPECT_LE(f.boneHausdorffMm, clean.boneHausdorffMm + 0.2);  // one-triangle holes, a voxel wide
}

}  // namespace
}  // namespace jawmesh::test
