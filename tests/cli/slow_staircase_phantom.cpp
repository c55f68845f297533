// The worse of the two cases of the soak bench (bench/soak.sh seeds=12 teeth=1,2,3, session 42)
// that kept a tet under 10 degrees: the phantom mandible with 2 teeth, seed 9, every tooth as
// unsmoothed voxels of 0.2 mm (bench_soak's "staircase" variant), at bench_soak's triangle scale.
// After every rung and refinement round one tet was left at 3.73 degrees (a PDL tet on a face of
// the staircase bent by about 4 degrees); the improver's final run with longer interface pushes
// (TetOptions::finalInterfacePushMm) mends it, and run.json says it was kept. (Seed 1's 9.69 is
// mended by the same stage, measured by the soak: docs/BENCHMARKS.md session 43; one case keeps
// the slow set's time down.)
#include "levelset/Phantom.h"
#include "support/TestData.h"
#include "support/VoxelStaircase.h"
#include "support_CliRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

nlohmann::json runStaircasePhantom(std::uint32_t seed) {
    const fs::path dir = test::scratchDir("staircase-phantom-s" + std::to_string(seed));
    PhantomOptions o;
    o.teeth = 2;
    o.seed = seed;
    o.trianglesScale = 0.25;  // bench_soak's default scale
    PhantomJaw jaw = makePhantom(o);
    for (auto& [unn, tooth] : jaw.teeth) tooth = test::voxelStaircase(tooth, 0.2);
    writePhantomCase({jaw}, (dir / "case").string());
    const test::CliResult r =
        test::runJawmesh("-q run " + (dir / "case").string() + " -o " + (dir / "out").string() + " --jaw mandible", dir / "run.log");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    std::ifstream in(dir / "out" / "mandible" / "run.json");
    return in ? nlohmann::json::parse(in) : nlohmann::json();
}

TEST(SlowStaircasePhantom, SoakCaseThatKeptASliverMeetsTenDegrees) {
    for (std::uint32_t seed : {9u}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const nlohmann::json run = runStaircasePhantom(seed);
        ASSERT_TRUE(run.contains("quality")) << run.dump();
        EXPECT_EQ(run["quality"]["tets_below_min_dihedral"].get<int>(), 0);
        EXPECT_GE(run["quality"]["min_dihedral_deg"].get<double>(), 10.0 - 1e-9);
        // the last improvement ran because a tet under 10 degrees was left, and its mesh was kept
        const nlohmann::json& push = run["tetgen"]["final_push"];
        ASSERT_TRUE(push.is_object()) << run["tetgen"].dump();
        EXPECT_TRUE(push["kept"].get<bool>());
        EXPECT_GE(push["improvement"]["below_target_before"].get<int>(), 1);
        EXPECT_EQ(push["improvement"]["below_target_after"].get<int>(), 0);
        EXPECT_TRUE(run["validation"]["valid"].get<bool>()) << run["validation"].dump();
    }
}

}  // namespace
}  // namespace jawmesh
