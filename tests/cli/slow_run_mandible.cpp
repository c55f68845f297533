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
    const std::vector<int> teeth = test::teethIn(input + "/teeth");
    ASSERT_EQ(teeth.size(), 14u);
    const test::RunFigures f = test::measureRun(run, input, "mandible", teeth);
    test::expectRunMeetsTargets(f, teeth);

    std::ifstream in(fs::path(run) / "run.json");
    const auto record = nlohmann::json::parse(in);
    EXPECT_EQ(record.at("mesh").at("tets").get<std::size_t>(), f.quality.tets);
}

}  // namespace
}  // namespace jawmesh
