// Label volumes (issue #23): NRRD, detached NRRD headers, 3D Slicer segmentations with layers,
// NIfTI-1 (.nii, .nii.gz) read back as written, oblique and anisotropic voxels included; every
// kind of bad file refused with its name; label roles from labels.json and from segment names;
// case folders holding a label volume.
#include "io/Case.h"
#include "io/Error.h"
#include "io/LabelRoles.h"
#include "io/LabelVolume.h"
#include "support/TestData.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <fstream>

namespace jawmesh::test {
namespace {
namespace fs = std::filesystem;

/// 12 x 9 x 7 voxels of 0.25 x 0.3 x 0.5 mm, turned 30 degrees about an oblique axis: bone (1)
/// below k = 3, a tooth (124) box inside, the rest 0.
LabelVolume smallVolume() {
    LabelVolume v;
    v.path = "small";
    v.size = {12, 9, 7};
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 6, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    v.directionsMm = turn * Vec3(0.25, 0.3, 0.5).asDiagonal();
    v.originMm = Vec3(-12.5, 3.25, 40.0);
    v.values.assign(v.voxels(), 0);
    for (int k = 0; k < 7; ++k)
        for (int j = 0; j < 9; ++j)
            for (int i = 0; i < 12; ++i) {
                std::int32_t& x = v.values[static_cast<std::size_t>((k * 9 + j) * 12 + i)];
                if (k < 3) x = 1;
                if (i >= 3 && i < 8 && j >= 2 && j < 6 && k >= 2 && k < 6) x = 124;
            }
    return v;
}

std::size_t countOf(const LabelVolume& v, std::int32_t value) {
    return static_cast<std::size_t>(std::count(v.values.begin(), v.values.end(), value));
}

void expectSameVolume(const LabelVolume& a, const LabelVolume& b, double geometryTolerance) {
    EXPECT_EQ(a.size, b.size);
    EXPECT_EQ(a.layers, b.layers);
    EXPECT_LT((a.directionsMm - b.directionsMm).cwiseAbs().maxCoeff(), geometryTolerance);
    EXPECT_LT((a.originMm - b.originMm).cwiseAbs().maxCoeff(), geometryTolerance);
    EXPECT_EQ(a.values, b.values);
}

/// Expects readLabelVolume(path) to throw an Error naming the file and containing `what`.
void expectRefused(const fs::path& path, const std::string& what) {
    try {
        readLabelVolume(path.string());
        ADD_FAILURE() << path << " was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
}

TEST(LabelVolume, ReadsBackWhatItWritesInEveryFormat) {
    const fs::path dir = scratchDir("label-volume-formats");
    const LabelVolume v = smallVolume();
    for (const std::string name : {"labels.nrrd", "labels.nii", "labels.nii.gz"}) {
        SCOPED_TRACE(name);
        writeLabelVolume(v, (dir / name).string());
        const LabelVolume back = readLabelVolume((dir / name).string());
        // NIfTI-1 keeps the sform in single precision.
        expectSameVolume(v, back, name == "labels.nrrd" ? 1e-12 : 1e-5);
        ASSERT_EQ(back.segments.size(), 2u);
        EXPECT_EQ(back.segments[0].value, 1);
        EXPECT_EQ(back.segments[0].voxelCount, countOf(v, 1));
        EXPECT_EQ(back.segments[1].value, 124);
        EXPECT_EQ(back.segments[1].voxelCount, countOf(v, 124));
        EXPECT_LT((back.worldOf(11, 8, 6) - v.worldOf(11, 8, 6)).norm(), 1e-4);
    }
    EXPECT_TRUE(fs::is_regular_file(dir / "labels.nrrd"));
    for (const auto& entry : fs::directory_iterator(dir))  // no temporary file left behind
        EXPECT_EQ(entry.path().filename().string().rfind(".tmp-", 0), std::string::npos) << entry.path();
}

// The NIfTI reader reads and converts its data a slab of 2^24 voxels at a time (a 0.1 mm jaw's
// 600 M voxels are not held twice): a volume just over one slab reads back value for value,
// compressed or not, and one cut short in its second slab is refused.
TEST(LabelVolume, ReadsANiftiLargerThanOneSlabAndRefusesItCut) {
    const fs::path dir = scratchDir("label-volume-slabs");
    LabelVolume v;
    v.path = "slabs";
    v.size = {256, 256, 257};
    v.directionsMm = Vec3(0.1, 0.1, 0.1).asDiagonal();
    v.values.resize(v.voxels());
    for (std::size_t n = 0; n < v.voxels(); ++n) v.values[n] = static_cast<std::int32_t>((n * 7919) % 301);
    for (const std::string name : {"big.nii", "big.nii.gz"}) {
        writeLabelVolume(v, (dir / name).string());
        expectSameVolume(v, readLabelVolume((dir / name).string()), 1e-6);
    }
    fs::copy_file(dir / "big.nii", dir / "cut.nii");
    fs::resize_file(dir / "cut.nii", fs::file_size(dir / "big.nii") - 1000);
    expectRefused(dir / "cut.nii", "truncated");
}

TEST(LabelVolume, ReadsASlicerSegmentationWithTwoLayers) {
    // Bone and tooth overlap in a layered segmentation: each on its own layer.
    LabelVolume v = smallVolume();
    v.layers = 2;
    std::vector<std::int32_t> layers(2 * v.voxels(), 0);
    for (std::size_t i = 0; i < v.voxels(); ++i) {
        layers[i] = v.values[i] == 0 ? 0 : 3;               // layer 0: the bone under everything
        layers[v.voxels() + i] = v.values[i] == 124 ? 1 : 0;  // layer 1: the tooth
    }
    v.values = layers;
    v.segments = {{0, 3, "Mandible", 0}, {1, 1, "Tooth 24", 0}};
    const fs::path path = scratchDir("label-volume-slicer") / "labels.seg.nrrd";
    writeLabelVolume(v, path.string(), true);
    const LabelVolume back = readLabelVolume(path.string());
    expectSameVolume(v, back, 1e-12);
    ASSERT_EQ(back.segments.size(), 2u);
    EXPECT_EQ(back.segments[0].name, "Mandible");
    EXPECT_EQ(back.segments[0].layer, 0);
    EXPECT_EQ(back.segments[0].voxelCount, countOf(smallVolume(), 1) + countOf(smallVolume(), 124));
    EXPECT_EQ(back.segments[1].name, "Tooth 24");
    EXPECT_EQ(back.segments[1].layer, 1);
    EXPECT_EQ(back.segments[1].voxelCount, countOf(smallVolume(), 124));
    const LabelAssignment roles = assignLabelRoles(back, Jaw::Mandible, "");
    EXPECT_EQ(roles.roles[0].kind, LabelRole::Kind::Bone);
    EXPECT_EQ(roles.roles[1].kind, LabelRole::Kind::Tooth);
    EXPECT_EQ(roles.roles[1].unn, 24);
}

TEST(LabelVolume, ReadsADetachedHeaderAndRefusesItsTruncatedData) {
    const fs::path dir = scratchDir("label-volume-nhdr");
    std::vector<std::uint8_t> data(4 * 3 * 2, 0);
    data[5] = 7;
    data[23] = 9;
    {
        std::ofstream raw(dir / "labels.raw", std::ios::binary);
        raw.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
        std::ofstream shortRaw(dir / "short.raw", std::ios::binary);
        shortRaw.write(reinterpret_cast<const char*>(data.data()), 10);
    }
    const std::string header = "NRRD0004\ntype: uint8\ndimension: 3\nspace: right-anterior-superior\nsizes: 4 3 2\n"
                               "space directions: (0.2,0,0) (0,0.2,0) (0,0,0.4)\nspace origin: (1,2,3)\nencoding: raw\n";
    test::writeText(dir / "labels.nhdr", header + "data file: labels.raw\n");
    const LabelVolume v = readLabelVolume((dir / "labels.nhdr").string());
    EXPECT_EQ(v.size, (std::array<int, 3>{4, 3, 2}));
    EXPECT_EQ(v.values[5], 7);
    EXPECT_EQ(v.values[23], 9);
    EXPECT_LT((v.worldOf(3, 2, 1) - Vec3(1.6, 2.4, 3.4)).norm(), 1e-12);
    test::writeText(dir / "short.nhdr", header + "data file: short.raw\n");
    expectRefused(dir / "short.nhdr", "cannot read as NRRD");
}

TEST(LabelVolume, RefusesEveryKindOfBadFileNamingIt) {
    const fs::path dir = scratchDir("label-volume-bad");
    std::vector<std::uint8_t> bytes(64, 1);
    {
        std::ofstream raw(dir / "data.raw", std::ios::binary);
        raw.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    }
    auto nhdr = [&](const std::string& name, const std::string& body) {
        test::writeText(dir / name, "NRRD0004\n" + body + "encoding: raw\ndata file: data.raw\n");
        return dir / name;
    };
    expectRefused(nhdr("flat.nhdr", "type: uint8\ndimension: 2\nsizes: 8 8\n"), "2D volume");
    expectRefused(nhdr("float.nhdr", "type: float\nendian: little\ndimension: 3\nsizes: 2 2 4\n"), "labels must be integers");
    expectRefused(nhdr("time.nhdr", "type: uint8\ndimension: 4\nsizes: 2 2 4 4\n"), "not a 3D Slicer layered segmentation");
    expectRefused(nhdr("metres.nhdr", "type: uint8\ndimension: 3\nsizes: 4 4 4\nspace: left-posterior-superior\n"
                                      "space directions: (0.0002,0,0) (0,0.0002,0) (0,0,0.0002)\nspace units: \"m\" \"m\" \"m\"\n"),
                  "metres");
    expectRefused(nhdr("flat-axes.nhdr", "type: uint8\ndimension: 3\nsizes: 4 4 4\nspace: left-posterior-superior\n"
                                         "space directions: (0.2,0,0) (0.4,0,0) (0,0,0.2)\n"),
                  "degenerate");
    std::vector<std::uint8_t> zeros(64, 0);
    {
        std::ofstream raw(dir / "zeros.raw", std::ios::binary);
        raw.write(reinterpret_cast<const char*>(zeros.data()), static_cast<std::streamsize>(zeros.size()));
    }
    test::writeText(dir / "empty.nhdr", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\ndata file: zeros.raw\n");
    expectRefused(dir / "empty.nhdr", "all background");
    test::writeText(dir / "labels.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 40 40 40\nencoding: gzip\n\nnot gzip data at all");
    expectRefused(dir / "labels.nrrd", "cannot read as NRRD");
    test::writeText(dir / "labels.nii", std::string(400, 'x'));
    expectRefused(dir / "labels.nii", "cannot read as NIfTI");
    // A NIfTI whose data stops early.
    writeLabelVolume(smallVolume(), (dir / "whole.nii").string());
    fs::copy_file(dir / "whole.nii", dir / "cut.nii");
    fs::resize_file(dir / "cut.nii", fs::file_size(dir / "whole.nii") - 100);
    expectRefused(dir / "cut.nii", "cannot read as NIfTI");
    expectRefused(dir / "missing.nii.gz", "no such file");
    // A size no file of this length can hold is refused before anything is allocated.
    test::writeText(dir / "huge.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 100000 100000 1000\nencoding: gzip\n\nxx");
    expectRefused(dir / "huge.nrrd", "more than its file(s) can hold");
}

TEST(LabelRoles, NamesFromSlicerAndFromLabelsJson) {
    LabelRole r;
    ASSERT_TRUE(roleFromName("Tooth 24", r));
    EXPECT_EQ(r.kind, LabelRole::Kind::Tooth);
    EXPECT_EQ(r.unn, 24);
    ASSERT_TRUE(roleFromName("pdl_31", r));
    EXPECT_EQ(r.kind, LabelRole::Kind::Pdl);
    EXPECT_EQ(r.unn, 31);
    for (const char* bone : {"mandible", "Maxilla", "bone", "Jaw"}) {
        ASSERT_TRUE(roleFromName(bone, r)) << bone;
        EXPECT_EQ(r.kind, LabelRole::Kind::Bone);
    }
    EXPECT_FALSE(roleFromName("Segment_3", r));
    EXPECT_FALSE(roleFromName("tooth", r));

    const fs::path dir = scratchDir("label-roles");
    LabelVolume v = readLabelVolume((writeLabelVolume(smallVolume(), (dir / "labels.nrrd").string()), (dir / "labels.nrrd").string()));
    test::writeText(dir / "labels.json", R"({"labels": {"1": "bone", "124": "tooth_24"}, "pdl": "generate"})");
    const LabelAssignment a = assignLabelRoles(v, Jaw::Mandible, (dir / "labels.json").string());
    EXPECT_EQ(a.roles[0].kind, LabelRole::Kind::Bone);
    EXPECT_EQ(a.roles[1].unn, 24);
    EXPECT_EQ(a.pdl, PdlLabels::Generate);
    auto refused = [&](const std::string& json, Jaw jaw, const std::string& what) {
        test::writeText(dir / "labels.json", json);
        try {
            assignLabelRoles(v, jaw, (dir / "labels.json").string());
            ADD_FAILURE() << json << " was taken";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("labels.json"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    // An unmapped label is listed with its voxel count.
    refused(R"({"labels": {"1": "bone"}})", Jaw::Mandible, "124: " + std::to_string(countOf(v, 124)) + " voxels");
    refused(R"({"labels": {"1": "bone", "124": "tooth_8"}})", Jaw::Mandible, "not a tooth of the mandible");
    refused(R"({"labels": {"1": "ignore", "124": "tooth_25"}})", Jaw::Mandible, "no label is bone");
    refused(R"({"labels": {"1": "bone", "124": "pdl_24"}})", Jaw::Mandible, "but no label of that tooth");
    refused(R"({"labels": {"1": "bone", "x": "tooth_24"}})", Jaw::Mandible, "not an integer");
    refused(R"({"labels": {"1": "enamel"}})", Jaw::Mandible, "is not bone");
    refused(R"({"labels": {"1": "bone", "124": "tooth_24"}, "pdl": "maybe"})", Jaw::Mandible, "\"pdl\"");
    refused(R"({"labels": [1, 2]})", Jaw::Mandible, "expected");
    refused("{not json", Jaw::Mandible, "not valid JSON");
    // Without labels.json plain values have no names: every label is listed.
    try {
        assignLabelRoles(v, Jaw::Mandible, "");
        ADD_FAILURE() << "plain values taken without names";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("1: " + std::to_string(countOf(v, 1)) + " voxels"), std::string::npos) << e.what();
    }
}

TEST(LabelVolumeCase, IsAJawOfItsOwnAndNeverBesideSurfaces) {
    const fs::path root = scratchDir("label-volume-case");
    const fs::path jaw = root / "input" / "mandible";
    writeLabelVolume(smallVolume(), (jaw / "labels.nii.gz").string());
    test::writeText(jaw / "labels.json", R"({"labels": {"1": "bone", "124": "tooth_24"}})");
    const CaseInfo info = discoverCase(root.string());
    ASSERT_EQ(info.jaws.size(), 1u);
    EXPECT_EQ(info.jaws[0].labelVolumePath, (jaw / "labels.nii.gz").string());
    EXPECT_EQ(info.jaws[0].labelsJsonPath, (jaw / "labels.json").string());
    EXPECT_EQ(info.jaws[0].folder, jaw.string());
    EXPECT_THROW(loadJaw(info.jaws[0]), Error);  // surfaces come through loadJawInput
    fs::create_directories(jaw / "bone");
    try {
        discoverCase(root.string());
        ADD_FAILURE() << "a label volume beside surfaces was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("labels.nii.gz"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("bone"), std::string::npos) << e.what();
    }
    fs::remove(jaw / "bone");
    writeLabelVolume(smallVolume(), (jaw / "labels.nrrd").string());
    EXPECT_THROW(discoverCase(root.string()), Error);
}

}  // namespace
}  // namespace jawmesh::test
