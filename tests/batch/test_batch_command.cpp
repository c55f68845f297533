// `jawmesh batch` end to end on the batch test dataset (tests/batch/make_test_dataset.sh: 6 light
// phantoms + 1 broken case): the first run completes 6 and reports the broken one with the
// reader's message and a non-zero exit; an immediate rerun reuses the 6 in seconds; after one
// finished mesh is deleted (and a batch redoing it is killed mid-task), the rerun redoes exactly
// that case, with identical outputs.
#include "batch/Manifest.h"
#include "io/ChildProcess.h"
#include "support/TestData.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <csignal>
#include <sys/wait.h>
#include <thread>

namespace jawmesh {
namespace {
namespace fs = std::filesystem;

const std::string kJawmesh = JAWMESH_BINARY;
const std::string kConfig = std::string(JAWMESH_SOURCE_DIR) + "/tests/batch/fast_phantom.json";

int exitCode(const std::string& command) {
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct BatchRun {
    int exitCode = -1;
    double seconds = 0;
    BatchManifest manifest;
};

BatchRun batch(const fs::path& dataset, const fs::path& out, const fs::path& log) {
    const auto start = std::chrono::steady_clock::now();
    BatchRun r;
    r.exitCode = exitCode(kJawmesh + " batch " + dataset.string() + " -o " + out.string() + " --config " + kConfig +
                          " > " + log.string() + " 2>&1");
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.manifest = readManifest(out.string());
    std::printf("[batch] run: exit %d, %.1f s\n", r.exitCode, r.seconds);
    return r;
}

/// The records that hold timings (run.json, report/report.json's "seconds"): equal runs differ there.
const std::set<std::string> kTimedRecords = {"run.json", "report/report.json"};

/// path -> checksum of a finished task's files (from its completion stamp), timed records aside.
std::map<std::string, std::string> stampedFiles(const fs::path& jawDir) {
    std::ifstream in(jawDir / "outputs.json");
    const auto stamp = nlohmann::json::parse(in);
    std::map<std::string, std::string> files;
    for (const auto& f : stamp.at("files"))
        if (!kTimedRecords.count(f.at("path").get<std::string>()))
            files[f.at("path").get<std::string>()] = f.at("checksum").get<std::string>();
    return files;
}

/// The evaluation report without its timing.
nlohmann::json untimedReport(const fs::path& jawDir) {
    std::ifstream in(jawDir / "report" / "report.json");
    nlohmann::json report = nlohmann::json::parse(in);
    report.erase("seconds");
    return report;
}

/// The pid in the name of the first in-flight folder (".<jaw>.partial-<host>-<pid>") to appear
/// under caseOut within a minute, or 0.
int waitForPartialFolder(const fs::path& caseOut) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
        std::error_code ec;
        for (fs::directory_iterator it(caseOut, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string name = it->path().filename().string();
            if (name.find(".partial-") != std::string::npos && name.find(".old") == std::string::npos)
                return std::stoi(name.substr(name.rfind('-') + 1));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return 0;
}

/// True once pid has exited (a zombie waiting for its new parent to reap it counts as exited).
bool waitUntilGone(int pid) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < deadline) {
        std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
        std::string pidText, command, state;
        if (!(stat >> pidText >> command >> state) || state == "Z" || state == "X") return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
}

bool hasPartialFolders(const fs::path& out) {
    for (const auto& e : fs::recursive_directory_iterator(out))
        if (e.path().filename().string().find(".partial-") != std::string::npos) return true;
    return false;
}

TEST(BatchCommand, CompletesReportsResumesAndRedoesOnlyDamagedCases) {
    const auto dir = test::scratchDir("batch-command");
    const fs::path dataset = dir / "dataset", out = dir / "out";
    ASSERT_EQ(exitCode("bash " + std::string(JAWMESH_SOURCE_DIR) + "/tests/batch/make_test_dataset.sh " + kJawmesh +
                       " " + dataset.string()),
              0);

    // First run: 6 ok, the broken case failed with the reader's message naming the file.
    const BatchRun first = batch(dataset, out, dir / "first.log");
    EXPECT_NE(first.exitCode, 0) << test::readText(dir / "first.log");
    ASSERT_EQ(first.manifest.tasks.size(), 7u);
    for (int k = 0; k < 6; ++k) {
        const TaskRecord& r = first.manifest.tasks[static_cast<std::size_t>(k)];
        EXPECT_EQ(r.task.caseName, "Patient_" + std::to_string(k + 1));
        EXPECT_EQ(r.status, TaskStatus::Ok) << r.task.caseName << ": " << r.error;
        EXPECT_FALSE(r.reused);
        EXPECT_GT(r.seconds, 0.0);
        EXPECT_GT(r.peakMemoryBytes, 50u * 1000 * 1000) << "the child's peak, measured by the kernel";
        EXPECT_GT(r.estimatedMemoryBytes, 0u);
        EXPECT_TRUE(fs::exists(out / r.task.caseName / "mandible" / "volumetric_meshes" / "mandible.msh"));
    }
    // Tasks run in a temporary folder that is renamed when complete: no output may name it.
    for (const auto& e : fs::recursive_directory_iterator(out / "Patient_1" / "mandible")) {
        if (e.is_regular_file()) {
            EXPECT_EQ(test::readText(e.path()).find(".partial-"), std::string::npos) << e.path() << " names the temporary folder";
        }
    }
    const TaskRecord& broken = first.manifest.tasks[6];
    EXPECT_EQ(broken.task.caseName, "Patient_7");
    EXPECT_EQ(broken.status, TaskStatus::Failed);
    EXPECT_NE(broken.error.find("Patient_7/input/mandible/bone/mandible.stl"), std::string::npos) << broken.error;
    EXPECT_FALSE(fs::exists(out / "Patient_7" / "mandible")) << "a failed case leaves no output folder";
    EXPECT_NE(test::readText(out / broken.log).find("mandible.stl"), std::string::npos) << "its log has the error";
    const std::string csv = test::readText(out / "summary.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 8) << csv;
    EXPECT_NE(test::readText(dir / "first.log").find("6 ok (0 reused), 1 failed, 0 pending"), std::string::npos);
    EXPECT_FALSE(hasPartialFolders(out));

    // Immediate rerun: the 6 are validated and reused in seconds; the broken one is retried.
    const BatchRun second = batch(dataset, out, dir / "second.log");
    EXPECT_NE(second.exitCode, 0);
    for (int k = 0; k < 6; ++k) {
        const TaskRecord& r = second.manifest.tasks[static_cast<std::size_t>(k)];
        EXPECT_EQ(r.status, TaskStatus::Ok);
        EXPECT_TRUE(r.reused) << r.task.caseName;
    }
    EXPECT_EQ(second.manifest.tasks[6].status, TaskStatus::Failed);
    EXPECT_LT(second.seconds, 15.0);

    // One finished mesh deleted, and the batch that redoes it killed (SIGKILL) mid-task: the task
    // in flight dies with it, the manifest stays readable and the other outputs untouched.
    const fs::path damaged = out / "Patient_3" / "mandible";
    const auto before = stampedFiles(damaged);
    const nlohmann::json reportBefore = untimedReport(damaged);
    fs::remove(damaged / "volumetric_meshes" / "mandible.msh");
    const int coordinator = startChild({kJawmesh, "batch", dataset.string(), "-o", out.string(), "--config", kConfig},
                                       (dir / "killed.log").string());
    const int task = waitForPartialFolder(out / "Patient_3");
    ASSERT_GT(task, 0) << test::readText(dir / "killed.log");
    ::kill(coordinator, SIGKILL);
    while (!reapFinishedChild()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_TRUE(waitUntilGone(task)) << "the task process outlived its batch";
    EXPECT_EQ(readManifest(out.string()).tasks.size(), 7u);
    EXPECT_TRUE(hasPartialFolders(out));

    // The rerun redoes exactly that case, to the same outputs, and clears the killed run's leftovers.
    const BatchRun third = batch(dataset, out, dir / "third.log");
    EXPECT_NE(third.exitCode, 0);
    for (int k = 0; k < 6; ++k) {
        const TaskRecord& r = third.manifest.tasks[static_cast<std::size_t>(k)];
        EXPECT_EQ(r.status, TaskStatus::Ok) << r.task.caseName << ": " << r.error;
        EXPECT_EQ(r.reused, r.task.caseName != "Patient_3") << r.task.caseName;
    }
    EXPECT_EQ(stampedFiles(damaged), before) << "the redone case's outputs equal the first run's";
    EXPECT_EQ(untimedReport(damaged), reportBefore);
    EXPECT_FALSE(hasPartialFolders(out));

    // --status agrees; --slurm (without --submit) writes an array of the one task left to do.
    EXPECT_NE(exitCode(kJawmesh + " --quiet batch --status " + out.string()), 0);
    EXPECT_EQ(readManifest(out.string()).tasks[6].status, TaskStatus::Failed);
    ASSERT_EQ(exitCode(kJawmesh + " --quiet batch " + dataset.string() + " -o " + out.string() + " --config " + kConfig +
                       " --slurm --mem 2G > /dev/null"),
              0);
    const std::string script = test::readText(out / "slurm" / "batch.sbatch");
    EXPECT_NE(script.find("#SBATCH --array=6\n"), std::string::npos) << script;
    EXPECT_NE(script.find("#SBATCH --mem=2G\n"), std::string::npos) << script;

    // A TetGen failure (here: an invalid quality bound) keeps the interface surface for study
    // beside the case's outputs, and the message names where it is.
    const fs::path one = dir / "one", oneOut = dir / "one-out";
    fs::create_directories(one);
    fs::copy(dataset / "Patient_1", one / "Patient_1", fs::copy_options::recursive);
    std::ifstream fastConfig(kConfig);
    nlohmann::json badTet = nlohmann::json::parse(fastConfig);
    badTet["tet_radius_edge"] = 0.5;
    test::writeText(dir / "bad_tet.json", badTet.dump());
    EXPECT_NE(exitCode(kJawmesh + " --quiet batch " + one.string() + " -o " + oneOut.string() + " --config " +
                       (dir / "bad_tet.json").string()),
              0);
    const TaskRecord tetFailure = readManifest(oneOut.string()).tasks.at(0);
    const fs::path kept = oneOut / "Patient_1" / "mandible.failed_surface" / "mandible.poly";
    EXPECT_EQ(tetFailure.status, TaskStatus::Failed);
    EXPECT_NE(tetFailure.error.find(kept.string()), std::string::npos) << tetFailure.error;
    EXPECT_GT(fs::file_size(kept), 1000u);
    EXPECT_FALSE(hasPartialFolders(oneOut));

    // Bad input is one clear error, and nothing is written.
    EXPECT_NE(exitCode(kJawmesh + " --quiet batch " + (dir / "missing").string() + " -o " + (dir / "out2").string() +
                       " 2> " + (dir / "err.txt").string()),
              0);
    EXPECT_NE(test::readText(dir / "err.txt").find("does not exist"), std::string::npos) << test::readText(dir / "err.txt");
    EXPECT_FALSE(fs::exists(dir / "out2"));
    test::writeText(dir / "typo.json", "{\"voxel_mn\": 0.2}");
    EXPECT_NE(exitCode(kJawmesh + " --quiet batch " + dataset.string() + " -o " + (dir / "out3").string() +
                       " --config " + (dir / "typo.json").string() + " 2> " + (dir / "err.txt").string()),
              0);
    EXPECT_NE(test::readText(dir / "err.txt").find("unknown config key 'voxel_mn'"), std::string::npos) << test::readText(dir / "err.txt");
    EXPECT_FALSE(fs::exists(dir / "out3"));
}

}  // namespace
}  // namespace jawmesh
