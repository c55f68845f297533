// `jawmesh run` on the phantom written as a label volume (issue #23): a 3D Slicer .seg.nrrd and a
// NIfTI .nii.gz of the same phantom give the same mesh; the mesh meets every target of a run
// against the surfaces of its labels; its volume is the labels' voxel volume; segmented PDL labels
// are kept with their voxel volume, or regenerated at the requested thickness on request.
#include "io/GmshReader.h"
#include "io/LabelRoles.h"
#include "io/LabelVolume.h"
#include "tet/ElementQuality.h"
#include "support/TestData.h"
#include "support_LabelCase.h"
#include "support_RunChecks.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

/// Voxel by voxel, the role its labels give (kind and UNN; 0 for none), so that two files that
/// number or name their labels differently compare as anatomy.
std::vector<int> voxelRoles(const LabelVolume& v) {
    const fs::path json = fs::path(v.path).parent_path() / "labels.json";
    const LabelAssignment a = assignLabelRoles(v, Jaw::Mandible, fs::exists(json) ? json.string() : "");
    std::vector<int> roles(v.voxels(), 0);
    for (std::size_t i = 0; i < v.segments.size(); ++i) {
        const LabelRole& r = a.roles[i];
        const int code = 1000 * (static_cast<int>(r.kind) + 1) + r.unn;
        for (std::size_t x = 0; x < v.voxels(); ++x)
            if (v.at(v.segments[i].layer, x) == v.segments[i].value) roles[x] = code;
    }
    return roles;
}

/// Voxel-to-world map of a volume: size, axes (spacing included) and origin, in mm.
std::vector<double> gridOf(const LabelVolume& v) {
    std::vector<double> g{double(v.size[0]), double(v.size[1]), double(v.size[2])};
    g.insert(g.end(), v.directionsMm.data(), v.directionsMm.data() + 9);
    for (int a = 0; a < 3; ++a) g.push_back(v.originMm[a]);
    return g;
}

TEST(RunLabelMap, SlicerAndNiftiGiveOneMeshThatMeetsTheTargets) {
    const fs::path dir = test::scratchDir("run-label-map");
    const std::string bin = JAWMESH_BINARY;
    // 0.125 mm: exact in NIfTI-1's single-precision transform, so both files hold the same grid.
    for (const std::string file : {"labels.seg.nrrd", "labels.nii.gz"}) {
        const std::string c = file == "labels.nii.gz" ? "nifti" : "slicer";
        const std::string make = bin + " -q phantom " + (dir / c).string() + " --teeth 1 --voxel 0.125 --label-map " + file;
        ASSERT_EQ(std::system(make.c_str()), 0) << make;
    }
    // The two files are one input: the same grid in world space and the same anatomy in every
    // voxel (Slicer's segment names against labels.json). The pipeline is deterministic, so one
    // run stands for both (Determinism.* runs the whole pipeline twice).
    const fs::path labelJaw = dir / "nifti" / "input" / "mandible";
    const LabelVolume slicer = readLabelVolume((dir / "slicer" / "input" / "mandible" / "labels.seg.nrrd").string());
    const LabelVolume nifti = readLabelVolume((labelJaw / "labels.nii.gz").string());
    EXPECT_EQ(gridOf(slicer), gridOf(nifti));
    EXPECT_TRUE(voxelRoles(slicer) == voxelRoles(nifti)) << "the two formats hold different anatomy";
    const std::string run = bin + " -q run " + (dir / "nifti").string() + " -o " + (dir / "out-nifti").string();
    ASSERT_EQ(std::system(run.c_str()), 0) << run;
    const fs::path msh = fs::path("mandible") / "volumetric_meshes" / "mandible.msh";

    test::writeLabelSurfaces(labelJaw.string(), (dir / "surfaces").string());
    const std::vector<int> teeth = test::teethIn((dir / "surfaces" / "teeth").string());
    ASSERT_EQ(teeth, std::vector<int>{24});
    const test::RunFigures f = test::measureRun((dir / "out-nifti" / "mandible").string(), (dir / "surfaces").string(), "mandible", teeth);
    test::expectRunMeetsTargets(f, teeth);

    // The mesh fills what the labels fill: bone, tooth and the PDL carved between them.
    std::size_t labelled = 0;
    for (const LabelSegment& s : nifti.segments) labelled += s.voxelCount;
    const double voxelMm3 = std::abs(nifti.directionsMm.determinant());
    const double meshMm3 = test::totalVolumeMm3(readGmsh((dir / "out-nifti" / msh).string()));
    std::cout << "mesh volume " << meshMm3 << " mm^3, labelled voxels " << labelled * voxelMm3 << " mm^3\n";
    EXPECT_NEAR(meshMm3 / (static_cast<double>(labelled) * voxelMm3), 1.0, 0.03);
}

/// run.json of a finished run.
nlohmann::json runRecord(const fs::path& out) {
    std::ifstream in(out / "mandible" / "run.json");
    return nlohmann::json::parse(in);
}

TEST(RunLabelMap, SegmentedPdlIsKeptWithItsVoxelVolumeOrRegenerated) {
    const fs::path dir = test::scratchDir("run-label-map-pdl");
    const std::string bin = JAWMESH_BINARY;
    const std::string make = bin + " -q phantom " + (dir / "case").string() + " --teeth 1 --voxel 0.15 --pdl-labels 0.2 --label-map labels.nrrd";
    ASSERT_EQ(std::system(make.c_str()), 0) << make;
    const fs::path jawDir = dir / "case" / "input" / "mandible";
    ASSERT_NE(test::readText(jawDir / "labels.json").find("pdl_24"), std::string::npos);
    const auto run = [&](const std::string& out) {
        const std::string cmd = bin + " -q run " + (dir / "case").string() + " -o " + (dir / out).string() + " 2> " + (dir / "err.txt").string();
        EXPECT_EQ(std::system(cmd.c_str()), 0) << test::readText(dir / "err.txt");
        return runRecord(dir / out);
    };

    // Kept (the default): every region holds its voxels' volume, the PDL as segmented (the phantom's
    // 0.2 mm labelled on a 0.15 mm grid is 0.15-0.3 mm thick), measured in the report, not judged.
    const nlohmann::json kept = run("kept");
    EXPECT_TRUE(kept.at("validation").at("valid").get<bool>()) << kept.at("validation").dump();
    EXPECT_GE(kept.at("quality").at("min_dihedral_deg").get<double>(), 10.0);
    EXPECT_EQ(kept.at("carve").at("options").at("pdl"), "kept");
    EXPECT_NE(kept.at("eval").at("line").get<std::string>().find("kept as segmented"), std::string::npos) << kept.at("eval").dump();
    const auto volumes = labelVolumesMm3(readGmsh((dir / "kept" / "mandible" / "volumetric_meshes" / "mandible.msh").string()));
    ASSERT_EQ(volumes.size(), 3u);  // bone, tooth 24, PDL 24
    for (const auto& [label, labelledMm3] : test::labelledVolumesMm3(jawDir.string())) {
        std::cout << labelName(label) << ": mesh " << volumes.at(label) << " mm^3, voxels " << labelledMm3 << " mm^3\n";
        // Issue #23's 3 %, the PDL 1.5-2 voxels thick included (-0.8 % since session 31; -4.1 % while
        // its field inside the root was raised by the facing test, docs/BENCHMARKS.md).
        EXPECT_NEAR(volumes.at(label) / labelledMm3, 1.0, 0.03) << labelName(label);
    }
    const auto& thickness = kept.at("carve").at("summary").at("teeth").at(0).at("thickness_mm");
    EXPECT_GT(thickness.at("mean").get<double>(), 0.21);  // thicker than a regenerated PDL: kept
    EXPECT_GT(thickness.at("p95").get<double>(), 0.27);

    // Regenerated on request: the PDL carved at the requested 0.2 mm. Carving alone tells (the
    // meshing of a generated PDL from a label map is SlicerAndNiftiGiveOneMeshThatMeetsTheTargets').
    const fs::path json = jawDir / "labels.json";
    std::string labels = test::readText(json);
    labels.insert(labels.rfind('}'), ", \"pdl\": \"generate\"");
    std::ofstream(json) << labels;
    const std::string carve = bin + " -q carve " + (dir / "case").string() + " -o " + (dir / "regenerated").string() + " 2> " +
                              (dir / "err.txt").string();
    ASSERT_EQ(std::system(carve.c_str()), 0) << test::readText(dir / "err.txt");
    const nlohmann::json regenerated = test::readJson(dir / "regenerated" / "mandible" / "summary.json");
    EXPECT_EQ(regenerated.at("options").at("pdl"), "generated");
    ASSERT_EQ(regenerated.at("teeth").size(), 1u);
    EXPECT_GT(regenerated.at("teeth").at(0).at("pdl_volume_mm3").get<double>(), 0.0);
    EXPECT_NEAR(regenerated.at("teeth").at(0).at("thickness_mm").at("mean").get<double>(), 0.2, 0.01);
}

}  // namespace
}  // namespace jawmesh
