// Case discovery, loading, unit check and all_teeth.obj numbering on small generated cases.
#include "io/Case.h"
#include "io/MeshIO.h"
#include "support/TestData.h"
#include "io/IoTestUtil.h"

#include <cmath>

namespace jawmesh::test {
namespace {
namespace fs = std::filesystem;

/// A toy arch in the LPS frame (+x patient left, +y posterior, +z superior): per tooth a box
/// (crown up for the mandible) and a bone socket box around its root. Teeth are listed from the
/// patient's left end of the arch to the right end.
struct ToyArch {
    std::vector<int> unns;
    std::vector<SurfaceMesh> teeth;
    SurfaceMesh bone;
};

ToyArch toyArch(Jaw jaw, const std::vector<int>& unnsLeftToRight) {
    ToyArch arch;
    arch.unns = unnsLeftToRight;
    const double up = jaw == Jaw::Mandible ? 1.0 : -1.0;  // crowns point occlusally
    for (std::size_t k = 0; k < unnsLeftToRight.size(); ++k) {
        // Slot along a full arch of 16 (0 = patient-left end): missing teeth leave gaps.
        const int unn = unnsLeftToRight[k];
        const int slot = jaw == Jaw::Mandible ? unn - 17 : 16 - unn;
        const double s = -1.0 + 2.0 * slot / 15.0;  // -1 left .. 1 right
        const Vec3 c(-25.0 * s, 30.0 * s * s, 50.0);
        const double w = (k % 3 == 0) ? 1.6 : 1.4;
        arch.teeth.push_back(boxMesh(c + Vec3(-w, -w, up > 0 ? -4 : -4), c + Vec3(w, w, 4)));
        // socket: covers the root half (the occlusal side of the tooth stays free)
        append(arch.bone, boxMesh(c + Vec3(-w - 1, -w - 1, up > 0 ? -3 : -1), c + Vec3(w + 1, w + 1, up > 0 ? 1 : 3)));
    }
    return arch;
}

/// Rotates a mesh by 180 degrees about the x axis (a proper rotation: anatomy is unchanged).
SurfaceMesh flipped(SurfaceMesh m) {
    for (Vec3& v : m.vertices) v = Vec3(v.x(), -v.y(), -v.z());
    return m;
}

SurfaceMesh combined(const std::vector<SurfaceMesh>& parts) {
    SurfaceMesh all;
    for (const SurfaceMesh& p : parts) append(all, p);
    return all;
}

void checkNumbering(const std::map<int, SurfaceMesh>& got, const ToyArch& arch, bool flip) {
    ASSERT_EQ(got.size(), arch.unns.size());
    for (std::size_t k = 0; k < arch.unns.size(); ++k) {
        ASSERT_TRUE(got.count(arch.unns[k])) << "missing UNN " << arch.unns[k];
        const SurfaceMesh expected = flip ? flipped(arch.teeth[k]) : arch.teeth[k];
        const BBox a = boundingBox(got.at(arch.unns[k])), b = boundingBox(expected);
        EXPECT_LT((a.min - b.min).norm() + (a.max - b.max).norm(), 1e-5) << "UNN " << arch.unns[k];
    }
}

TEST(NumberTeethAlongArch, MandibleAndMaxillaFollowTheUniversalNumbering) {
    const std::vector<int> mandible = {18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31};
    const ToyArch m = toyArch(Jaw::Mandible, mandible);
    std::vector<std::string> notes;
    checkNumbering(numberTeethAlongArch(combined(m.teeth), Jaw::Mandible, m.bone, &notes), m, false);
    ASSERT_EQ(notes.size(), 1u);
    EXPECT_NE(notes[0].find("bone"), std::string::npos) << notes[0];

    // Maxilla: patient left end is 16, right end 1; here 1..15 (no 16) listed left to right.
    std::vector<int> maxilla;
    for (int u = 15; u >= 1; --u) maxilla.push_back(u);
    const ToyArch x = toyArch(Jaw::Maxilla, maxilla);
    checkNumbering(numberTeethAlongArch(combined(x.teeth), Jaw::Maxilla, x.bone), x, false);
}

TEST(NumberTeethAlongArch, UsesTheBoneNotTheFrameToFindTheOcclusalSide) {
    const std::vector<int> unns = {20, 21, 22, 23, 24, 25, 26, 27, 28};
    const ToyArch m = toyArch(Jaw::Mandible, unns);
    // Rotated 180 degrees about x, +z is now inferior; the bone still tells crowns from roots.
    std::vector<SurfaceMesh> teeth;
    for (const SurfaceMesh& t : m.teeth) teeth.push_back(flipped(t));
    checkNumbering(numberTeethAlongArch(combined(teeth), Jaw::Mandible, flipped(m.bone)), m, true);
}

TEST(NumberTeethAlongArch, JoinsNestedShellsAndDropsSpecks) {
    const std::vector<int> unns = {22, 23, 24, 25, 26, 27};
    ToyArch m = toyArch(Jaw::Mandible, unns);
    SurfaceMesh all = combined(m.teeth);
    const BBox first = boundingBox(m.teeth[0]);
    const Vec3 mid = 0.5 * (first.min + first.max);
    SurfaceMesh pulp = boxMesh(mid - Vec3(0.3, 0.3, 1), mid + Vec3(0.3, 0.3, 1));
    std::reverse(pulp.triangles.begin(), pulp.triangles.end());
    append(all, pulp);
    SurfaceMesh speck;  // one lone triangle far from the teeth
    speck.vertices = {Vec3(0, 80, 50), Vec3(0.1, 80, 50), Vec3(0, 80.1, 50)};
    speck.triangles = {{0, 1, 2}};
    append(all, speck);
    std::vector<std::string> notes;
    const auto teeth = numberTeethAlongArch(all, Jaw::Mandible, m.bone, &notes);
    ASSERT_EQ(teeth.size(), unns.size());
    EXPECT_EQ(teeth.at(22).triangles.size(), 24u);  // outer box + pulp box
    EXPECT_EQ(teeth.at(23).triangles.size(), 12u);
    EXPECT_NE(notes[0].find("joined"), std::string::npos) << notes[0];
    EXPECT_NE(notes[0].find("dropped"), std::string::npos) << notes[0];
}

TEST(NumberTeethAlongArch, RefusesMoreThanEightTeethPerSide) {
    const ToyArch m = toyArch(Jaw::Mandible, {17, 18, 19, 20, 21, 22, 23, 24, 25, 26});
    SurfaceMesh all = combined(m.teeth);
    SurfaceMesh bone = m.bone;
    for (int extra = 1; extra <= 2; ++extra) {  // two more teeth behind 17 on the left branch
        SurfaceMesh t = m.teeth[0];
        for (Vec3& v : t.vertices) v += Vec3(0.8 * extra, 4.0 * extra, 0);
        append(all, t);
    }
    EXPECT_THROW(numberTeethAlongArch(all, Jaw::Mandible, bone), Error);
}

/// Writes a toy case folder; returns its root.
fs::path writeToyCase(const std::string& name, Jaw jaw, const ToyArch& arch, double unit = 1.0, bool allTeeth = false) {
    const fs::path root = scratchDir(name);
    const fs::path jawDir = root / "input" / jawName(jaw);
    auto scaled = [unit](SurfaceMesh m) {
        for (Vec3& v : m.vertices) v *= unit;
        return m;
    };
    writeSurface(scaled(arch.bone), (jawDir / "bone" / (jawName(jaw) + ".stl")).string());
    if (allTeeth) {
        writeSurface(scaled(combined(arch.teeth)), (jawDir / "teeth" / "all_teeth.obj").string());
    } else {
        const char* exts[] = {"stl", "obj", "ply", "off"};
        for (std::size_t k = 0; k < arch.unns.size(); ++k) {
            const std::string ext = exts[k % 4];
            const fs::path p = jawDir / "teeth" / ("tooth_" + std::to_string(arch.unns[k]) + "." + (ext == "off" ? "stl" : ext));
            writeSurface(scaled(arch.teeth[k]), p.string());
        }
    }
    return root;
}

TEST(Case, DiscoversAndLoadsAToyMandible) {
    const ToyArch arch = toyArch(Jaw::Mandible, {22, 23, 24, 25, 26, 27});
    const fs::path root = writeToyCase("io-case-toy", Jaw::Mandible, arch);
    writeBytes(root / "input" / "mandible" / "teeth_axes_mandible.json",
               R"({"24": {"c": [0,0,0], "x": [1,0,0], "y": [0,1,0], "z": [0,0,1]}, "30": {"c": [0,0,0], "x": [1,0,0], "y": [0,1,0], "z": [0,0,1]}})");
    writeBytes(root / "input" / "mandible" / "teeth" / "README.txt", "not a surface");
    const CaseInfo info = discoverCase(root.string());
    ASSERT_EQ(info.jaws.size(), 1u);
    const JawCase& jc = info.jaws[0];
    EXPECT_EQ(jc.jaw, Jaw::Mandible);
    EXPECT_EQ(jc.toothPaths.size(), 6u);
    EXPECT_FALSE(jc.teethFromAllTeethObj);
    EXPECT_NE(jc.axesPath.find("teeth_axes_mandible.json"), std::string::npos);
    const JawSurfaces s = loadJaw(jc);
    EXPECT_EQ(s.bone.triangles.size(), arch.bone.triangles.size());
    checkNumbering(s.teeth, arch, false);
    EXPECT_EQ(s.axes.size(), 2u);
    ASSERT_EQ(s.notes.size(), 1u);  // axes of tooth 30 have no tooth
    EXPECT_NE(s.notes[0].find("30"), std::string::npos);
}

TEST(Case, AllTeethObjIsSplitAndNumbered) {
    const ToyArch arch = toyArch(Jaw::Maxilla, {12, 11, 10, 9, 8, 7, 6, 5, 4});
    const fs::path root = writeToyCase("io-case-allteeth", Jaw::Maxilla, arch, 1.0, true);
    const CaseInfo info = discoverCase(root.string());
    ASSERT_EQ(info.jaws.size(), 1u);
    EXPECT_TRUE(info.jaws[0].teethFromAllTeethObj);
    const JawSurfaces s = loadJaw(info.jaws[0]);
    checkNumbering(s.teeth, arch, false);
    ASSERT_FALSE(s.notes.empty());
    EXPECT_NE(s.notes[0].find("12 11 10 9 8 7 6 5 4"), std::string::npos) << s.notes[0];
}

TEST(Case, MetresAreRefusedUnlessAScaleIsGiven) {
    const ToyArch arch = toyArch(Jaw::Mandible, {23, 24, 25, 26});
    const fs::path root = writeToyCase("io-case-metres", Jaw::Mandible, arch, 0.001);
    const JawCase jc = discoverCase(root.string()).jaws.at(0);
    expectErrorNaming([&] { loadJaw(jc); }, "mandible.stl", "metres");
    expectErrorNaming([&] { loadJaw(jc); }, "mandible.stl", "scale");
    LoadOptions options;
    options.scale = 1000;
    const JawSurfaces s = loadJaw(jc, options);
    EXPECT_NEAR(boundingBox(s.bone).size().norm(), boundingBox(arch.bone).size().norm(), 1e-3);
    options.scale = -1;
    EXPECT_THROW(loadJaw(jc, options), Error);
}

TEST(Case, DiscoveryErrorsNameTheProblem) {
    const ToyArch arch = toyArch(Jaw::Mandible, {24, 25, 26});
    const std::string missing = (scratchDir("io-case-errors") / "nope").string();
    expectErrorNaming([&] { discoverCase(missing); }, missing, "does not exist");

    const fs::path noInput = scratchDir("io-case-noinput");
    expectErrorNaming([&] { discoverCase(noInput.string()); }, noInput.string(), "input/");
    fs::create_directories(noInput / "input" / "upper");
    expectErrorNaming([&] { discoverCase(noInput.string()); }, "input", "no jaw");

    auto withCase = [&](const std::string& name, const std::function<void(const fs::path& jawDir)>& spoil,
                        const std::string& file, const std::string& fragment) {
        const fs::path root = writeToyCase(name, Jaw::Mandible, arch);
        spoil(root / "input" / "mandible");
        SCOPED_TRACE(name);
        expectErrorNaming([&] { discoverCase(root.string()); }, file, fragment);
    };
    withCase("io-case-nobone", [](const fs::path& j) { fs::remove_all(j / "bone"); }, "mandible", "no bone");
    withCase("io-case-twobones", [&](const fs::path& j) { writeSurface(arch.bone, (j / "bone" / "mandible.obj").string()); },
             "bone", "several bone");
    withCase("io-case-noteeth", [](const fs::path& j) { fs::remove_all(j / "teeth"); }, "mandible", "no teeth");
    withCase("io-case-dup", [&](const fs::path& j) { writeSurface(arch.teeth[0], (j / "teeth" / "tooth_24.ply").string()); },
             "tooth_24", "twice");
    withCase("io-case-range", [&](const fs::path& j) { writeSurface(arch.teeth[0], (j / "teeth" / "tooth_40.stl").string()); },
             "tooth_40.stl", "outside 1..32");
    withCase("io-case-otherjaw", [&](const fs::path& j) { writeSurface(arch.teeth[0], (j / "teeth" / "tooth_5.stl").string()); },
             "tooth_5.stl", "maxilla");
    withCase("io-case-name", [&](const fs::path& j) { writeSurface(arch.teeth[0], (j / "teeth" / "molar.stl").string()); },
             "molar.stl", "tooth_<UNN>");
    withCase("io-case-both", [&](const fs::path& j) { writeSurface(arch.teeth[0], (j / "teeth" / "all_teeth.obj").string()); },
             "all_teeth.obj", "both");
}

TEST(Case, LoadReportsTheBrokenFile) {
    const ToyArch arch = toyArch(Jaw::Mandible, {24, 25, 26});
    const fs::path root = writeToyCase("io-case-broken", Jaw::Mandible, arch);
    const fs::path broken = root / "input" / "mandible" / "teeth" / "tooth_25.obj";
    writeBytes(broken, "v 0 0 0\nf 1 2 3\n");
    const JawCase jc = discoverCase(root.string()).jaws.at(0);
    expectErrorNaming([&] { loadJaw(jc); }, broken.string(), "outside");
}

}  // namespace
}  // namespace jawmesh::test
