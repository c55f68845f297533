// The same case and options give byte-identical outputs whatever the thread count: a one-tooth
// phantom run with --threads 1 and with every core. Only the records of timings (run.json and
// report/report.json) may differ; their mesh figures must not.
#include "support/TestData.h"
#include "support_CliRun.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <thread>

namespace jawmesh::test {
namespace {
namespace fs = std::filesystem;

std::string bytesOf(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

nlohmann::json jsonOf(const fs::path& p) { return nlohmann::json::parse(bytesOf(p)); }

TEST(Determinism, OneThreadAndAllThreadsGiveIdenticalFiles) {
    const fs::path dir = scratchDir("determinism");
    ASSERT_EQ(runJawmesh("-q phantom " + (dir / "case").string() + " --teeth 1 --seed 3 --triangles-scale 0.3",
                         dir / "phantom.log")
                  .exitCode,
              0);
    for (const char* threads : {"1", "0"}) {
        const CliResult r = runJawmesh("-q --threads " + std::string(threads) + " run " + (dir / "case").string() +
                                           " -o " + (dir / ("out" + std::string(threads))).string() + " --config " +
                                           fastConfig(),
                                       dir / ("run" + std::string(threads) + ".log"));
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    std::printf("[determinism] threads: 1 vs %u\n", std::thread::hardware_concurrency());
    const fs::path one = dir / "out1" / "mandible", all = dir / "out0" / "mandible";
    const std::vector<std::string> files = filesUnder(one);
    EXPECT_EQ(files, filesUnder(all));
    ASSERT_GT(files.size(), 10u);
    std::size_t compared = 0;
    for (const std::string& f : files) {
        if (f == "run.json" || f == "report/report.json") continue;
        EXPECT_TRUE(bytesOf(one / f) == bytesOf(all / f)) << f << " differs between 1 and all threads";
        ++compared;
    }
    std::printf("[determinism] %zu files byte-identical\n", compared);
    const nlohmann::json a = jsonOf(one / "run.json"), b = jsonOf(all / "run.json");
    for (const char* key : {"mesh", "quality", "validation"}) EXPECT_EQ(a.at(key), b.at(key)) << key;
    for (const char* key : {"vertices", "triangles", "seeds"}) EXPECT_EQ(a.at("surface").at(key), b.at("surface").at(key)) << key;
}

}  // namespace
}  // namespace jawmesh::test
