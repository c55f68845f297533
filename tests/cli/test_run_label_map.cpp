// `jawmesh run` on the phantom written as a label volume (issue #23): a 3D Slicer .seg.nrrd and a
// NIfTI .nii.gz of the same phantom give the same mesh; the mesh meets every target of a run
// against the surfaces of its labels; its volume is the labels' voxel volume; segmented PDL labels
// are refused until asked to be regenerated, then meshed.
#include "io/GmshReader.h"
#include "io/LabelVolume.h"
#include "support/TestData.h"
#include "support_LabelCase.h"
#include "support_RunChecks.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

std::string fileText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(RunLabelMap, SlicerAndNiftiGiveOneMeshThatMeetsTheTargets) {
    const fs::path dir = test::scratchDir("run-label-map");
    const std::string bin = JAWMESH_BINARY;
    // 0.125 mm: exact in NIfTI-1's single-precision transform, so both files hold the same grid.
    for (const std::string file : {"labels.seg.nrrd", "labels.nii.gz"}) {
        const std::string c = file == "labels.nii.gz" ? "nifti" : "slicer";
        const std::string make = bin + " -q phantom " + (dir / c).string() + " --teeth 1 --voxel 0.125 --label-map " + file;
        ASSERT_EQ(std::system(make.c_str()), 0) << make;
        const std::string run = bin + " -q run " + (dir / c).string() + " -o " + (dir / ("out-" + c)).string();
        ASSERT_EQ(std::system(run.c_str()), 0) << run;
    }
    const fs::path msh = fs::path("mandible") / "volumetric_meshes" / "mandible.msh";
    EXPECT_EQ(fileText(dir / "out-slicer" / msh), fileText(dir / "out-nifti" / msh)) << "the two formats gave different meshes";

    const fs::path labelJaw = dir / "nifti" / "input" / "mandible";
    test::writeLabelSurfaces(labelJaw.string(), (dir / "surfaces").string());
    const std::vector<int> teeth = test::teethIn((dir / "surfaces" / "teeth").string());
    ASSERT_EQ(teeth, std::vector<int>{24});
    const test::RunFigures f = test::measureRun((dir / "out-nifti" / "mandible").string(), (dir / "surfaces").string(), "mandible", teeth);
    test::expectRunMeetsTargets(f, teeth);

    // The mesh fills what the labels fill: bone, tooth and the PDL carved between them.
    const LabelVolume v = readLabelVolume((labelJaw / "labels.nii.gz").string());
    std::size_t labelled = 0;
    for (const LabelSegment& s : v.segments) labelled += s.voxelCount;
    const double voxelMm3 = std::abs(v.directionsMm.determinant());
    const double meshMm3 = test::totalVolumeMm3(readGmsh((dir / "out-nifti" / msh).string()));
    std::cout << "mesh volume " << meshMm3 << " mm^3, labelled voxels " << labelled * voxelMm3 << " mm^3\n";
    EXPECT_NEAR(meshMm3 / (static_cast<double>(labelled) * voxelMm3), 1.0, 0.03);
}

TEST(RunLabelMap, SegmentedPdlIsRefusedUnlessRegenerated) {
    const fs::path dir = test::scratchDir("run-label-map-pdl");
    const std::string bin = JAWMESH_BINARY;
    const std::string make = bin + " -q phantom " + (dir / "case").string() + " --teeth 1 --voxel 0.15 --pdl-labels 0.2 --label-map labels.nrrd";
    ASSERT_EQ(std::system(make.c_str()), 0) << make;
    const fs::path json = dir / "case" / "input" / "mandible" / "labels.json";
    ASSERT_NE(fileText(json).find("pdl_24"), std::string::npos);
    const std::string run = bin + " -q run " + (dir / "case").string() + " -o " + (dir / "out").string() + " 2> " + (dir / "err.txt").string();
    EXPECT_NE(std::system(run.c_str()), 0);
    const std::string err = fileText(dir / "err.txt");
    EXPECT_NE(err.find("labels.nrrd"), std::string::npos) << err;
    EXPECT_NE(err.find("\"pdl\": \"generate\""), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(dir / "out" / "mandible" / "volumetric_meshes" / "mandible.msh"));

    std::string labels = fileText(json);
    labels.insert(labels.rfind('}'), ", \"pdl\": \"generate\"");
    std::ofstream(json) << labels;
    ASSERT_EQ(std::system(run.c_str()), 0) << fileText(dir / "err.txt");
    std::ifstream in(dir / "out" / "mandible" / "run.json");
    const auto record = nlohmann::json::parse(in);
    EXPECT_TRUE(record.at("validation").at("valid").get<bool>()) << record.at("validation").dump();
    EXPECT_EQ(record.at("validation").at("tets_per_label").size(), 3u);  // bone, tooth 24, PDL 24
    EXPECT_GE(record.at("quality").at("min_dihedral_deg").get<double>(), 10.0);
}

}  // namespace
}  // namespace jawmesh
