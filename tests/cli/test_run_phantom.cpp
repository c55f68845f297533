// `jawmesh run` end to end on a one-tooth phantom: the figures issue #5 asks of every run, measured
// from the written files (tests/cli/support_RunChecks.h), not from the pipeline's own report.
#include "io/HugePageMalloc.h"
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

TEST(RunPhantom, MeshMeetsTheConformityQualityAndAccuracyTargets) {
    const fs::path dir = test::scratchDir("run-phantom");
    const std::string bin = JAWMESH_BINARY;
    ASSERT_EQ(std::system((bin + " -q phantom " + (dir / "case").string() + " --teeth 1").c_str()), 0);
    // without the test environment's allocator settings: the binary chooses its own
    const std::string run = "env -u GLIBC_TUNABLES " + bin + " -q run " + (dir / "case").string() + " -o " + (dir / "out").string();
    ASSERT_EQ(std::system(run.c_str()), 0) << run;

    const fs::path input = dir / "case" / "input" / "mandible";
    const std::vector<int> teeth = test::teethIn((input / "teeth").string());
    ASSERT_EQ(teeth.size(), 1u);
    const test::RunFigures f = test::measureRun((dir / "out" / "mandible").string(), input.string(), "mandible", teeth);
    test::expectRunMeetsTargets(f, teeth);

    // run.json agrees with what was measured here
    std::ifstream in(dir / "out" / "mandible" / "run.json");
    const auto record = nlohmann::json::parse(in);
    EXPECT_EQ(record.at("mesh").at("tets").get<std::size_t>(), f.quality.tets);
    EXPECT_NEAR(record.at("quality").at("min_dihedral_deg").get<double>(), f.quality.minDihedralDeg, 1e-6);
    // the binary re-executed itself for huge pages where the kernel waits to be asked
    const std::string mode = kernelHugePageMode();
    EXPECT_EQ(record.at("huge_pages").at("kernel_mode").get<std::string>(), mode);
    EXPECT_EQ(record.at("huge_pages").at("malloc_advises").get<bool>(), mode == "madvise");
}

}  // namespace
}  // namespace jawmesh
