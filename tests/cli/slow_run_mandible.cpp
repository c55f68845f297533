// `jawmesh run` on the shared OpenMandible: every figure issue #5 asks of the mesh, measured from
// the written files (support_RunChecks.h), on a finished run. quickstart.sh makes that run once
// (`jawmesh run ../shared/data/openmandible`, ~15-45 min on 2 cores) and points
// JAWMESH_MANDIBLE_RUN=<out>/mandible at it for this test and SlowEval's; without it the test skips.
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

TEST(SlowRunMandible, MeshMeetsTheConformityQualityAndAccuracyTargets) {
    const char* run = std::getenv("JAWMESH_MANDIBLE_RUN");
    if (!run) GTEST_SKIP() << "set JAWMESH_MANDIBLE_RUN=<out>/mandible (a finished run of the shared mandible)";
    const std::string input = test::sharedData("openmandible/input/mandible");
    JAWMESH_REQUIRE_SHARED(input);
    std::vector<int> teeth;
    for (const auto& e : fs::directory_iterator(fs::path(input) / "teeth")) {
        const std::string name = e.path().stem().string();
        if (name.rfind("tooth_", 0) == 0) teeth.push_back(std::stoi(name.substr(6)));
    }
    std::sort(teeth.begin(), teeth.end());
    ASSERT_EQ(teeth.size(), 14u);

    const test::RunFigures f = test::measureRun(run, input, "mandible", teeth);
    std::printf("tets %zu, min dihedral %.2f deg (%zu below 10), bone Hausdorff %.3f mm\n", f.quality.tets,
                f.quality.minDihedralDeg, f.quality.belowDihedralThreshold, f.boneHausdorffMm);
    for (int u : teeth)
        std::printf("tooth %d: PDL thickness mean %.4f mm, Hausdorff %.3f mm\n", u, f.pdlThicknessMeanMm.at(u),
                    f.toothHausdorffMm.at(u));

    EXPECT_TRUE(f.validation.valid()) << (f.validation.messages.empty() ? "" : f.validation.messages.front());
    EXPECT_EQ(f.validation.nonManifoldFaces + f.validation.coincidentFaces + f.validation.invertedTets +
                  f.validation.duplicateNodes + f.validation.degenerateTets,
              0u);
    EXPECT_TRUE(f.validation.missingTeeth.empty() && f.validation.missingPdls.empty());
    EXPECT_GE(f.quality.minDihedralDeg, 10.0);
    EXPECT_LE(f.quality.tets, 800000u);
    for (int u : teeth) {
        EXPECT_NEAR(f.pdlThicknessMeanMm.at(u), 0.20, 0.01) << "tooth " << u;
        EXPECT_LE(f.toothHausdorffMm.at(u), 0.15) << "tooth " << u;
    }
    EXPECT_LE(f.boneHausdorffMm, 0.25);

    std::ifstream in(fs::path(run) / "run.json");
    const auto record = nlohmann::json::parse(in);
    EXPECT_EQ(record.at("mesh").at("tets").get<std::size_t>(), f.quality.tets);
}

}  // namespace
}  // namespace jawmesh
