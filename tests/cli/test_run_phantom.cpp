// `jawmesh run` end to end on a one-tooth phantom: the figures issue #5 asks of every run, measured
// from the written files (tests/cli/support_RunChecks.h), not from the pipeline's own report.
#include "support/TestData.h"
#include "support_RunChecks.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

std::vector<int> teethIn(const fs::path& teethDir) {
    std::vector<int> unn;
    for (const auto& e : fs::directory_iterator(teethDir)) {
        const std::string name = e.path().stem().string();  // tooth_<UNN>
        if (name.rfind("tooth_", 0) == 0) unn.push_back(std::stoi(name.substr(6)));
    }
    std::sort(unn.begin(), unn.end());
    return unn;
}

TEST(RunPhantom, MeshMeetsTheConformityQualityAndAccuracyTargets) {
    const fs::path dir = test::scratchDir("run-phantom");
    const std::string bin = JAWMESH_BINARY;
    ASSERT_EQ(std::system((bin + " -q phantom " + (dir / "case").string() + " --teeth 1").c_str()), 0);
    const std::string run = bin + " -q run " + (dir / "case").string() + " -o " + (dir / "out").string();
    ASSERT_EQ(std::system(run.c_str()), 0) << run;

    const fs::path input = dir / "case" / "input" / "mandible";
    const std::vector<int> teeth = teethIn(input / "teeth");
    ASSERT_EQ(teeth.size(), 1u);
    const test::RunFigures f = test::measureRun((dir / "out" / "mandible").string(), input.string(), "mandible", teeth);
    std::printf("tets %zu, min dihedral %.2f deg (%zu below 10), bone Hausdorff %.3f mm\n", f.quality.tets, f.quality.minDihedralDeg,
                f.quality.belowDihedralThreshold, f.boneHausdorffMm);
    for (int u : teeth)
        std::printf("tooth %d: PDL thickness mean %.4f mm, Hausdorff %.3f mm\n", u, f.pdlThicknessMeanMm.at(u), f.toothHausdorffMm.at(u));

    EXPECT_TRUE(f.validation.valid()) << (f.validation.messages.empty() ? "" : f.validation.messages.front());
    EXPECT_EQ(f.validation.nonManifoldFaces + f.validation.coincidentFaces + f.validation.invertedTets +
                  f.validation.duplicateNodes + f.validation.degenerateTets,
              0u);
    EXPECT_TRUE(f.validation.missingTeeth.empty() && f.validation.missingPdls.empty());
    EXPECT_GE(f.quality.minDihedralDeg, 10.0);
    EXPECT_EQ(f.quality.belowDihedralThreshold, 0u);
    EXPECT_LE(f.quality.tets, 800000u);
    for (int u : teeth) {
        EXPECT_NEAR(f.pdlThicknessMeanMm.at(u), 0.20, 0.01) << "tooth " << u;
        EXPECT_LE(f.toothHausdorffMm.at(u), 0.15) << "tooth " << u;
    }
    EXPECT_LE(f.boneHausdorffMm, 0.25);

    // run.json agrees with what was measured here
    std::ifstream in(dir / "out" / "mandible" / "run.json");
    const auto record = nlohmann::json::parse(in);
    EXPECT_EQ(record.at("mesh").at("tets").get<std::size_t>(), f.quality.tets);
    EXPECT_NEAR(record.at("quality").at("min_dihedral_deg").get<double>(), f.quality.minDihedralDeg, 1e-6);
}

}  // namespace
}  // namespace jawmesh
