// A user interrupt stops `jawmesh run` cleanly: Ctrl-C (SIGINT) and SIGTERM (kill, scancel) make
// the run stop at its next safe point with exit code 130, and leave no output: no jaw folder, no
// staging folder, no temporary file.
#include "io/ChildProcess.h"
#include "support/TestData.h"
#include "support_CliRun.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <iterator>
#include <sys/wait.h>
#include <thread>

namespace jawmesh::test {
namespace {
namespace fs = std::filesystem;

/// Starts a default-options run (minutes: still reading or making level sets after a second),
/// sends `signal` a second after the start (once its staging folder exists) and checks how it stopped.
void expectCleanStop(int signal, const std::string& name) {
    const fs::path dir = scratchDir(name);
    ASSERT_EQ(runJawmesh("-q phantom " + (dir / "case").string() + " --teeth 2", dir / "phantom.log").exitCode, 0);
    const fs::path out = dir / "out";
    const auto launched = std::chrono::steady_clock::now();
    const int pid = startChild({JAWMESH_BINARY, "run", (dir / "case").string(), "-o", out.string()}, (dir / "run.log").string());
    // The run is in flight, writing into its staging folder, when the signal comes.
    bool staging = false;
    while (!staging && std::chrono::steady_clock::now() - launched < std::chrono::seconds(30)) {
        staging = !leftoversUnder(dir).empty();
        if (!staging) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    EXPECT_TRUE(staging) << "no staging folder appeared";
    std::this_thread::sleep_until(launched + std::chrono::seconds(1));
    ASSERT_EQ(::kill(pid, signal), 0);
    int status = 0;
    const auto start = std::chrono::steady_clock::now();
    while (::waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() - start > std::chrono::seconds(120)) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            FAIL() << "the run did not stop within 2 minutes of the signal";
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("[interrupt] signal %d: stopped %.1f s after it\n", signal, seconds);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << " instead of stopping";
    EXPECT_EQ(WEXITSTATUS(status), 130);
    std::ifstream log(dir / "run.log");
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("cancelled by the user; no partial output written"), std::string::npos) << text;
    EXPECT_TRUE(filesUnder(out).empty()) << filesUnder(out).front();
    EXPECT_FALSE(fs::exists(out / "mandible"));
    EXPECT_TRUE(leftoversUnder(dir).empty()) << leftoversUnder(dir).front();
}

TEST(Interrupt, CtrlCStopsTheRunWithoutOutputs) { expectCleanStop(SIGINT, "interrupt-sigint"); }

TEST(Interrupt, SigtermStopsTheRunWithoutOutputs) { expectCleanStop(SIGTERM, "interrupt-sigterm"); }

}  // namespace
}  // namespace jawmesh::test
