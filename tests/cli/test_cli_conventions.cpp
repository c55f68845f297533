// The command-line conventions the README promises (issue #25): global options before or after the
// subcommand, usage errors as one line and exit code 2, defaults in --help, a bash completion
// script generated from the parser, machine-readable output alone on stdout.
#include "cli/RunOptions.h"
#include "support/TestData.h"
#include "support_CliRun.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace jawmesh::test {
namespace {

namespace fs = std::filesystem;

/// A one-tooth phantom case, made once for the tests of this file.
const fs::path& phantomCase() {
    static const fs::path dir = [] {
        const fs::path d = processScratchDir("cli-conventions") / "case";
        const CliResult r = runJawmesh("phantom " + d.string() + " --teeth 1 --quiet", d.parent_path() / "phantom.log");
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return d;
    }();
    return dir;
}

TEST(CliConventions, GlobalOptionsAfterTheSubcommandWork) {
    const fs::path out = scratchDir("cli-global-after") / "out";
    const CliResult r = runJawmesh("run " + phantomCase().string() + " -o " + out.string() + " --config " + fastConfig() +
                                       " --quiet --threads 1",
                                   out.parent_path() / "run.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fs::exists(out / "mandible" / "run.json"));
    // --quiet was taken: no progress lines (TerminalProgress writes "[stage] ...").
    EXPECT_EQ(r.output.find("done in"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find('%'), std::string::npos) << r.output;
}

TEST(CliConventions, UsageErrorsAreOneLineWithExitCodeTwo) {
    const fs::path dir = scratchDir("cli-usage-errors");
    const std::string caseDir = phantomCase().string();
    // arguments -> what the line must name
    const std::pair<std::string, std::string> cases[] = {
        {"run --bogus", "--bogus"},
        {"run " + caseDir + " -o " + (dir / "o").string() + " --bogus", "--bogus"},
        {"run " + caseDir, "--output"},
        {"carve " + caseDir + " -o " + (dir / "o").string() + " --voxel -1", "--voxel"},
        {"carve " + caseDir + " -o " + (dir / "o").string() + " --voxel abc", "--voxel"},
        {"run " + caseDir + " -o " + (dir / "o").string() + " --jaw jaw", "--jaw"},
        {"--threads -2 demo", "--threads"},
        {"demo --threads x", "--threads"},
        {"completion zsh", "zsh"},
        {"nocommand", "nocommand"},
    };
    for (const auto& [args, named] : cases) {
        const CliResult r = runJawmesh(args, dir / "usage.log");
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
        EXPECT_EQ(r.output.rfind("jawmesh: usage error: ", 0), 0u) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(named), std::string::npos) << args << "\n" << r.output;
        EXPECT_NE(r.output.find("--help`"), std::string::npos) << args << "\n" << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "o"));
}

TEST(CliConventions, HelpShowsDefaultsAndUnits) {
    const fs::path dir = scratchDir("cli-help");
    const CliResult carve = runJawmesh("carve --help", dir / "carve.log");
    ASSERT_EQ(carve.exitCode, 0) << carve.output;
    EXPECT_NE(carve.output.find("--voxel FLOAT:POSITIVE=0.05"), std::string::npos) << carve.output;
    EXPECT_NE(carve.output.find("--pdl-thickness FLOAT:POSITIVE=0.2"), std::string::npos) << carve.output;
    EXPECT_NE(carve.output.find("PDL thickness, mm"), std::string::npos) << carve.output;
    // run's voxel is a placeholder until the config is read: help shows the real default.
    const CliResult run = runJawmesh("run --help", dir / "run.log");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("--voxel FLOAT:POSITIVE=0.05"), std::string::npos) << run.output;
    const CliResult surface = runJawmesh("surface --help", dir / "surface.log");
    EXPECT_NE(surface.output.find("--min-angle FLOAT:FLOAT in [0 - 59]=15"), std::string::npos) << surface.output;
    // one source of defaults: `surface` makes from a carve the surface that `run` makes (issue #22)
    EXPECT_NE(surface.output.find("--pdl-max-edge FLOAT:POSITIVE=0.8"), std::string::npos) << surface.output;
    EXPECT_EQ(defaultRunOptions().simplify.pdlMaxEdgeMm, 0.8);
}

TEST(CliConventions, BashCompletionCompletesCommandsAndOptions) {
    const fs::path dir = scratchDir("cli-completion");
    const fs::path script = dir / "jawmesh.bash";
    ASSERT_EQ(std::system((std::string(JAWMESH_BINARY) + " completion bash > " + script.string()).c_str()), 0);
    // words typed so far (the last is being completed) -> completions, space-separated
    const std::pair<std::string, std::string> cases[] = {
        {"jawmesh ru", "run"},
        {"jawmesh run case --wr", "--write-levelsets"},
        {"jawmesh -q carve --pdl-t", "--pdl-thickness"},
        {"jawmesh surface dir --qu", "--quiet"},
        {"jawmesh --ver", "--version"},
    };
    for (const auto& [typed, expected] : cases) {
        std::istringstream words(typed);
        std::string w, array;
        int n = 0;
        while (words >> w) array += (n++ ? " " : "") + w;
        const fs::path out = dir / "reply.txt";
        const std::string command = "bash -c 'source " + script.string() + "; COMP_WORDS=(" + array + "); COMP_CWORD=" +
                                    std::to_string(n - 1) + "; _jawmesh; echo \"${COMPREPLY[*]}\"' > " + out.string();
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        std::string reply = test::readText(out);
        while (!reply.empty() && reply.back() == '\n') reply.pop_back();
        EXPECT_EQ(reply, expected) << typed;
    }
}

TEST(CliConventions, JsonAloneOnStdoutProgressOnStderr) {
    const fs::path dir = scratchDir("cli-json-stdout");
    const fs::path bone = phantomCase() / "input" / "mandible" / "bone" / "mandible.stl";
    ASSERT_TRUE(fs::exists(bone));
    // Not quiet: progress is printed, and must go to stderr.
    const std::string command = std::string(JAWMESH_BINARY) + " levelset " + bone.string() + " -o " + (dir / "bone.vdb").string() +
                                " --voxel 0.3 --json > " + (dir / "out.txt").string() + " 2> " + (dir / "err.txt").string();
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    const std::string out = test::readText(dir / "out.txt");
    const nlohmann::json j = nlohmann::json::parse(out);  // throws when anything else is on stdout
    EXPECT_TRUE(j.is_object());
    EXPECT_FALSE(test::readText(dir / "err.txt").empty());
}

}  // namespace
}  // namespace jawmesh::test
