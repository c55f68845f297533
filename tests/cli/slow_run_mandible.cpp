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

/// The finished run `run` of the shared jaw whose input is `inputRelative` (in ../shared/data),
/// with `teethCount` teeth, against the run targets; its figures in f.
void checkSharedRun(const std::string& run, const std::string& inputRelative, const std::string& jaw, std::size_t teethCount,
                    test::RunFigures& f) {
    const std::string input = test::sharedData(inputRelative);
    JAWMESH_REQUIRE_SHARED(input);
    const std::vector<int> teeth = test::teethIn(input + "/teeth");
    ASSERT_EQ(teeth.size(), teethCount);
    f = test::measureRun(run, input, jaw, teeth);
    test::expectRunMeetsTargets(f, teeth);
}

TEST(SlowRunMandible, MeshMeetsTheConformityQualityAndAccuracyTargets) {
    const char* run = std::getenv("JAWMESH_MANDIBLE_RUN");
    if (!run) GTEST_SKIP() << "set JAWMESH_MANDIBLE_RUN=<out>/mandible (a finished run of the shared mandible)";
    test::RunFigures f;
    checkSharedRun(run, "openmandible/input/mandible", "mandible", 14, f);
    if (HasFatalFailure() || IsSkipped()) return;

    std::ifstream in(fs::path(run) / "run.json");
    const auto record = nlohmann::json::parse(in);
    EXPECT_EQ(record.at("mesh").at("tets").get<std::size_t>(), f.quality.tets);
    // The bone far from the teeth took blocks one level larger (AdaptiveOptions::farBoneExtraLevels),
    // and every figure above holds with them.
    EXPECT_GT(record.at("surface").at("adaptive").at("far_bone_blocks").get<std::size_t>(), 0u);
}

// The shared maxilla the same way (issue #22: "passes the same mesh checks"); its 15 real teeth.
TEST(SlowRunMandible, MaxillaRunMeetsTheConformityQualityAndAccuracyTargets) {
    const char* run = std::getenv("JAWMESH_MAXILLA_RUN");
    if (!run) GTEST_SKIP() << "set JAWMESH_MAXILLA_RUN=<out>/maxilla (a finished run of the shared maxilla)";
    test::RunFigures f;
    checkSharedRun(run, "p26-maxilla-teeth/input/maxilla", "maxilla", 15, f);
}

}  // namespace
}  // namespace jawmesh
