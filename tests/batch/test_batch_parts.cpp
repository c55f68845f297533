// The parts of a batch on small folders made in the test: checksums and completion stamps (what a
// resume trusts), dataset discovery, manifest records, the memory-aware schedule, child processes
// (exit codes, crashes, peak memory), the folder lock, the Slurm script and the summary.
#include "batch/BatchLayout.h"
#include "batch/Checksum.h"
#include "batch/Dataset.h"
#include "batch/FolderLock.h"
#include "batch/Manifest.h"
#include "batch/MemoryEstimate.h"
#include "batch/OutputStamp.h"
#include "batch/Schedule.h"
#include "batch/SlurmScript.h"
#include "batch/Summary.h"
#include "io/ChildProcess.h"
#include "io/Error.h"
#include "support/TestData.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

namespace jawmesh {
namespace {
namespace fs = std::filesystem;

ChildExit waitForChild(int pid) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < deadline) {
        if (auto e = reapFinishedChild()) {
            if (e->pid == pid) return *e;
            continue;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ADD_FAILURE() << "child " << pid << " did not finish";
    return {};
}

TEST(BatchChecksum, DetectsAnyChangeAndStreamsFilesInBlocks) {
    const std::string a(3 * (1u << 20) + 5, 'x');  // crosses the 1 MiB read blocks at odd offsets
    std::string b = a;
    b[2 * (1u << 20) + 1] = 'y';
    EXPECT_EQ(checksumHex(a), checksumHex(a));
    EXPECT_NE(checksumHex(a), checksumHex(b));
    EXPECT_NE(checksumHex(a), checksumHex(a + std::string(1, '\0')));  // the length counts
    EXPECT_NE(checksumHex(""), checksumHex(std::string(1, '\0')));
    EXPECT_EQ(checksumHex(a).size(), 16u);
    const auto dir = test::scratchDir("batch-checksum");
    test::writeText(dir / "a.bin", a);
    EXPECT_EQ(fileChecksumHex((dir / "a.bin").string()), checksumHex(a));
    EXPECT_THROW(fileChecksumHex((dir / "missing.bin").string()), Error);
}

TEST(BatchOutputStamp, ValidOnlyForTheSameOptionsAndUnchangedFiles) {
    const auto dir = test::scratchDir("batch-stamp");
    test::writeText(dir / "run.json", "{}\n");
    test::writeText(dir / "volumetric_meshes" / "mandible.msh", "mesh contents");
    OutputStamp stamp;
    stamp.optionsHash = "h1";
    stamp.seconds = 12.5;
    stamp.peakMemoryBytes = 123456;
    stamp.files = stampFiles(dir.string());
    ASSERT_EQ(stamp.files.size(), 2u);
    EXPECT_EQ(stamp.files[0].path, "run.json");
    EXPECT_EQ(stamp.files[1].path, "volumetric_meshes/mandible.msh");
    writeOutputStamp(stamp, dir.string());
    EXPECT_EQ(stampFiles(dir.string()).size(), 2u) << "the stamp never lists itself";

    const std::vector<std::string> required = {"run.json", "volumetric_meshes/mandible.msh"};
    OutputStamp read;
    EXPECT_EQ(outputProblem(dir.string(), "h1", required, &read), "");
    EXPECT_EQ(read.seconds, 12.5);
    EXPECT_EQ(read.peakMemoryBytes, 123456u);
    EXPECT_NE(outputProblem(dir.string(), "h2", required).find("other options"), std::string::npos);
    EXPECT_NE(outputProblem(dir.string(), "h1", {"volumetric_meshes/mandible.vtu"}).find("does not list"),
              std::string::npos);

    test::writeText(dir / "volumetric_meshes" / "mandible.msh", "mesh Contents");  // same size, other bytes
    EXPECT_NE(outputProblem(dir.string(), "h1", required).find("contents changed"), std::string::npos);
    test::writeText(dir / "volumetric_meshes" / "mandible.msh", "mesh");  // truncated
    EXPECT_NE(outputProblem(dir.string(), "h1", required).find("bytes"), std::string::npos);
    fs::remove(dir / "volumetric_meshes" / "mandible.msh");
    EXPECT_NE(outputProblem(dir.string(), "h1", required).find("missing"), std::string::npos);
    test::writeText(dir / kOutputStampName, "{\"status\": ");
    EXPECT_NE(outputProblem(dir.string(), "h1", required).find("unreadable stamp"), std::string::npos);
    fs::remove(dir / kOutputStampName);
    EXPECT_NE(outputProblem(dir.string(), "h1", required).find("no completion stamp"), std::string::npos);
}

TEST(BatchDataset, OneTaskPerCaseAndJawAndBrokenCasesAreTasksToo) {
    const auto ds = test::scratchDir("batch-dataset");
    for (const char* jaw : {"mandible", "maxilla"}) {
        test::writeText(ds / "Patient_2" / "input" / jaw / "bone" / (std::string(jaw) + ".stl"), "");
        test::writeText(ds / "Patient_2" / "input" / jaw / "teeth" / (std::string(jaw) == "mandible" ? "tooth_24.stl" : "tooth_8.stl"), "");
    }
    test::writeText(ds / "Patient_1" / "input" / "mandible" / "bone" / "mandible.stl", "");
    test::writeText(ds / "Patient_1" / "input" / "mandible" / "teeth" / "tooth_25.stl", "");
    fs::create_directories(ds / "Patient_3" / "scans");   // no input/: reported, not skipped
    fs::create_directories(ds / ".cache");                 // hidden: ignored
    test::writeText(ds / "README.txt", "not a case");            // files beside the cases: ignored

    const std::vector<DatasetTask> tasks = discoverDataset(ds.string());
    ASSERT_EQ(tasks.size(), 4u);
    EXPECT_EQ(taskName(tasks[0]), "Patient_1/mandible");
    EXPECT_EQ(taskName(tasks[1]), "Patient_2/mandible");
    EXPECT_EQ(taskName(tasks[2]), "Patient_2/maxilla");
    EXPECT_EQ(taskName(tasks[3]), "Patient_3");
    EXPECT_TRUE(tasks[3].jaw.empty());
    EXPECT_NE(tasks[3].discoveryError.find("no input/ folder"), std::string::npos) << tasks[3].discoveryError;
    EXPECT_TRUE(fs::path(tasks[0].caseDir).is_absolute());

    fs::create_directories(ds / "out" / "Patient_1");  // a batch's output folder inside the dataset
    EXPECT_EQ(discoverDataset(ds.string(), (ds / "out").string()).size(), 4u);

    EXPECT_THROW(discoverDataset((ds / "nope").string()), Error);
    try {
        discoverDataset((ds / "Patient_1").string());
        FAIL() << "a case folder is not a dataset";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("is a case folder"), std::string::npos) << e.what();
    }
    const auto empty = test::scratchDir("batch-dataset-empty");
    EXPECT_THROW(discoverDataset(empty.string()), Error);
}

TEST(BatchManifest, RoundTripsAndTaskResultsAreReadBack) {
    const auto out = test::scratchDir("batch-manifest");
    BatchManifest m;
    m.datasetDir = "/data/set";
    m.jawmeshVersion = "9.9";
    m.options = {{"voxel_mm", 0.1}};
    m.optionsHash = "abc";
    TaskRecord r;
    r.task = {"Patient_1", "/data/set/Patient_1", "mandible", ""};
    r.status = TaskStatus::Failed;
    r.seconds = 3.5;
    r.peakMemoryBytes = 1u << 30;
    r.estimatedMemoryBytes = 2u << 30;
    r.error = "bone.stl: truncated, \"expected\" 80 bytes";
    r.log = "logs/Patient_1.mandible.log";
    r.optionsHash = "abc";
    m.tasks.push_back(r);
    writeManifest(m, out.string());
    const BatchManifest back = readManifest(out.string());
    EXPECT_EQ(toJson(back), toJson(m));

    EXPECT_FALSE(readTaskResult(out.string(), r.task));
    writeTaskResult(r, out.string());
    const auto result = readTaskResult(out.string(), r.task);
    ASSERT_TRUE(result);
    EXPECT_EQ(toJson(*result), toJson(r));

    test::writeText(manifestPath(out.string()), "[1, 2");
    try {
        readManifest(out.string());
        FAIL() << "a torn manifest must be an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), manifestPath(out.string()));
    }

    const std::string csv = summaryCsv(m);
    EXPECT_NE(csv.find("\"bone.stl: truncated, \"\"expected\"\" 80 bytes\""), std::string::npos) << csv;
    const std::string table = summaryTable(m);
    EXPECT_NE(table.find("Patient_1  mandible  failed"), std::string::npos) << table;
    EXPECT_NE(table.find("0 ok (0 reused), 1 failed, 0 pending"), std::string::npos) << table;
}

TEST(BatchSchedule, StartsTasksOnlyWhenTheirMemoryFits) {
    const std::uint64_t gb = 1000000000;
    // Nothing runs: the first task starts even when it alone exceeds the budget.
    EXPECT_EQ(nextTaskToStart({5 * gb, 1 * gb}, 0, 0, 2, 4 * gb), std::optional<std::size_t>(0));
    // One runs with 3 GB of 4: the 2 GB task waits, the 1 GB one behind it may start.
    EXPECT_EQ(nextTaskToStart({2 * gb, 1 * gb}, 1, 3 * gb, 2, 4 * gb), std::optional<std::size_t>(1));
    EXPECT_EQ(nextTaskToStart({2 * gb, 2 * gb}, 1, 3 * gb, 4, 4 * gb), std::nullopt);
    // The job cap holds whatever the memory.
    EXPECT_EQ(nextTaskToStart({1, 1}, 2, 2, 2, 100 * gb), std::nullopt);
    EXPECT_EQ(nextTaskToStart({}, 0, 0, 2, 100 * gb), std::nullopt);
}

TEST(BatchMemoryEstimate, GrowsWithAreaAndFinerVoxels) {
    SurfaceMesh cube;  // unit cube, 12 triangles: area 6 mm^2
    cube.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    cube.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                      {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    EXPECT_NEAR(surfaceAreaMm2(cube), 6.0, 1e-12);
    EXPECT_LT(estimateRunMemoryBytes(1000, 0.1), estimateRunMemoryBytes(2000, 0.1));
    EXPECT_LT(estimateRunMemoryBytes(1000, 0.1), estimateRunMemoryBytes(1000, 0.05));
    EXPECT_GT(availableMemoryBytes(), 0u);
    // Absurd voxels saturate instead of wrapping around to a small estimate.
    EXPECT_EQ(estimateRunMemoryBytes(1000, 1e-12), std::numeric_limits<std::uint64_t>::max());
}

TEST(BatchMemoryEstimate, RequireMemoryFitsRefusesWithTheVoxelThatWouldFit) {
    JawSurfaces jaw;
    jaw.bone.vertices = {{0, 0, 0}, {100, 0, 0}, {0, 100, 0}};  // 5,000 mm^2
    jaw.bone.triangles = {{0, 1, 2}};
    const std::uint64_t needed = estimateJawMemoryBytes(jaw, 0.05);
    EXPECT_EQ(needed, estimateRunMemoryBytes(5000, 0.05));
    EXPECT_NO_THROW(requireMemoryFits(jaw, 0.05, needed, "case"));
    EXPECT_NO_THROW(requireMemoryFits(jaw, 0.05, 0, "case"));  // unknown: no check
    try {
        requireMemoryFits(jaw, 0.05, needed / 4, "case/input/mandible");
        ADD_FAILURE() << "no Error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind("case/input/mandible: ", 0), 0u) << what;
        const std::size_t at = what.find("a voxel of ", what.find("available"));
        ASSERT_NE(at, std::string::npos) << what;
        const double fits = std::stod(what.substr(at + 11));
        EXPECT_GT(fits, 0.05);
        EXPECT_LE(estimateJawMemoryBytes(jaw, fits), needed / 4) << what;  // the suggestion does fit
    }
}

TEST(BatchChildProcess, ExitCodesCrashesPeakMemoryAndLogs) {
    const auto dir = test::scratchDir("batch-child");
    const std::string log = (dir / "logs" / "a.log").string();
    const int ok = startChild({"/bin/sh", "-c", "echo to-stdout; echo to-stderr >&2; exit 3"}, log);
    const ChildExit e = waitForChild(ok);
    EXPECT_EQ(e.exitCode, 3);
    EXPECT_EQ(e.signal, 0);
    EXPECT_GT(e.peakMemoryBytes, 0u);
    EXPECT_EQ(describeExit(e), "exit code 3");
    const std::string text = test::readText(log);
    EXPECT_NE(text.find("to-stdout"), std::string::npos);
    EXPECT_NE(text.find("to-stderr"), std::string::npos);

    const ChildExit crash = waitForChild(startChild({"/bin/sh", "-c", "kill -SEGV $$"}, log));
    EXPECT_EQ(crash.signal, 11);
    EXPECT_NE(describeExit(crash).find("signal 11"), std::string::npos);

    const ChildExit missing = waitForChild(startChild({(dir / "no-such-program").string()}, log));
    EXPECT_EQ(missing.exitCode, 127);
    EXPECT_TRUE(fs::path(currentExecutablePath()).is_absolute());
}

TEST(BatchFolderLock, OneCoordinatorPerOutputFolder) {
    const auto dir = test::scratchDir("batch-lock");
    {
        FolderLock first(dir.string());
        EXPECT_THROW(FolderLock second(dir.string()), Error);
    }
    EXPECT_NO_THROW(FolderLock again(dir.string()));
}

TEST(BatchLayout, CommitReplacesTheOldOutputsAndStalePartialsGo) {
    const auto out = test::scratchDir("batch-layout");
    const DatasetTask task{"Patient_1", "/x/Patient_1", "mandible", ""};
    const fs::path finalDir = taskOutputDir(out.string(), task);
    test::writeText(finalDir / "old.txt", "old");
    const std::string partial = taskPartialDir(out.string(), task);
    EXPECT_EQ(fs::path(partial).parent_path(), finalDir.parent_path());
    test::writeText(fs::path(partial) / "new.txt", "new");
    commitTaskOutput(partial, finalDir.string());
    EXPECT_TRUE(fs::exists(finalDir / "new.txt"));
    EXPECT_FALSE(fs::exists(finalDir / "old.txt"));
    EXPECT_FALSE(fs::exists(partial));

    test::writeText(fs::path(taskPartialDir(out.string(), task)) / "half.msh", "half");
    const DatasetTask other{"Patient_1", "/x/Patient_1", "maxilla", ""};
    test::writeText(fs::path(taskPartialDir(out.string(), other)) / "half.msh", "half");
    removeStalePartials(out.string(), task);
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(out / "Patient_1")) left.push_back(e.path().filename().string());
    std::sort(left.begin(), left.end());
    ASSERT_EQ(left.size(), 2u);
    EXPECT_EQ(left[0].rfind(".maxilla.partial-", 0), 0u) << "another jaw's work is not touched";
    EXPECT_EQ(left[1], "mandible");
}

TEST(BatchSlurmScript, OneArrayTaskPerWaitingJawAndLogsPerTask) {
    EXPECT_EQ(arraySpec({0, 1, 2, 3, 5, 7, 8}), "0-3,5,7-8");
    EXPECT_EQ(arraySpec({4}), "4");
    EXPECT_EQ(arraySpec({}), "");
    EXPECT_EQ(slurmMemory(1), "1G");
    EXPECT_EQ(slurmMemory(3ull << 30), "3G");
    EXPECT_EQ(slurmMemory((3ull << 30) + 1), "4G");
    SlurmOptions o;
    o.partition = "short";
    o.time = "1:00:00";
    o.mem = "4G";
    o.cpus = 3;
    const std::string s = sbatchScript(o, "/opt/jawmesh", "/scratch/o'ut", {0, 2, 3});
    for (const char* line : {"#SBATCH --array=0,2-3\n", "#SBATCH --cpus-per-task=3\n", "#SBATCH --mem=4G\n",
                             "#SBATCH --time=1:00:00\n", "#SBATCH --partition=short\n",
                             "#SBATCH --output=/scratch/o'ut/logs/slurm-%A_%a.log\n",
                             "batch --array-task \"$SLURM_ARRAY_TASK_ID\" -o '/scratch/o'\\''ut'\n"})
        EXPECT_NE(s.find(line), std::string::npos) << line << "\nin\n" << s;
    EXPECT_EQ(s.find("--partition", s.find("--partition") + 1), std::string::npos);
    const std::string bare = sbatchScript(SlurmOptions{}, "/opt/jawmesh", "/o", {1});
    EXPECT_EQ(bare.find("--time"), std::string::npos) << "no limit unless asked: the partition's default applies";
}

}  // namespace
}  // namespace jawmesh
