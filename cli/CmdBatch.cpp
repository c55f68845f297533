// jawmesh batch: every (case, jaw) of a dataset, resumable, locally in child processes or as a
// Slurm job array; --array-task runs one task (what both kinds of batch start), --status collects.
#include "batch/BatchLayout.h"
#include "batch/BatchPlan.h"
#include "batch/Dataset.h"
#include "batch/FolderLock.h"
#include "batch/Manifest.h"
#include "batch/MemoryEstimate.h"
#include "batch/OptionsHash.h"
#include "batch/RunLocal.h"
#include "batch/SlurmScript.h"
#include "batch/Summary.h"
#include "cli/BatchTask.h"
#include "cli/Commands.h"
#include "cli/NumberChecks.h"
#include "cli/Pipeline.h"
#include "io/AtomicFile.h"
#include "io/ChildProcess.h"
#include "io/Error.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <thread>

namespace jawmesh {
namespace fs = std::filesystem;
namespace {

struct BatchArgs {
    std::string dataset;
    std::string outDir;
    std::string config;
    std::string edits;
    int jobs = 0;
    double memoryGb = 0;
    bool slurm = false;
    bool submit = false;
    SlurmOptions slurmOptions;
    long arrayTask = -1;
    std::string statusDir;
};

/// Share of the available memory a local batch plans to fill (the rest absorbs estimate errors).
constexpr double kMemoryBudgetShare = 0.9;

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

/// The batch's options (defaults + --config) as recorded in options.json and hashed.
nlohmann::json batchOptions(const BatchArgs& args) {
    RunOptions options = defaultRunOptions();
    if (!args.config.empty()) applyRunConfig(args.config, options);
    if (!args.edits.empty()) options.edits = readEditFile(args.edits);
    if (!options.fromVdb.empty())
        throw Error(args.config, "from_vdb names one case's level sets; it cannot apply to a whole batch");
    return runOptionsToJson(options);
}

/// Plans the batch and writes options.json and the manifest (before any task starts, so a task
/// always finds both).
BatchManifest prepare(const BatchArgs& args, const std::string& out) {
    const nlohmann::json options = batchOptions(args);
    BatchManifest m = planBatch(absolute(args.dataset), out, options, optionsHash(options, JAWMESH_VERSION), JAWMESH_VERSION);
    writeFileAtomically(optionsPath(out), [&](std::ostream& o) { o << options.dump(2) << '\n'; }, false);
    writeManifest(m, out);
    return m;
}

/// Writes summary.csv, prints the table, and fails (non-zero exit) unless every task is ok.
void finish(const BatchManifest& m, const std::string& out, const GlobalOptions& global) {
    writeFileAtomically(summaryCsvPath(out), [&](std::ostream& o) { o << summaryCsv(m); }, false);
    if (!global.quiet) std::printf("%s", summaryTable(m).c_str());
    std::fflush(stdout);
    const StatusCounts c = countStatuses(m);
    if (c.failed + c.pending > 0)
        throw Error(manifestPath(out), std::to_string(c.failed) + " failed and " + std::to_string(c.pending) +
                                           " unfinished of " + std::to_string(m.tasks.size()) + " tasks (see " +
                                           summaryCsvPath(out) + ")");
}

/// Checks the dataset and the config before the output folder is created, so bad input leaves
/// nothing behind.
void checkInputs(const BatchArgs& args, const std::string& out) {
    discoverDataset(args.dataset, out);
    batchOptions(args);
}

void runLocal(const BatchArgs& args, const GlobalOptions& global) {
    const std::string out = absolute(args.outDir);
    checkInputs(args, out);
    FolderLock lock(out);
    BatchManifest m = prepare(args, out);
    const int pending = static_cast<int>(std::count_if(m.tasks.begin(), m.tasks.end(),
                                                       [](const TaskRecord& r) { return r.status == TaskStatus::Pending; }));
    const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    LocalBatchOptions local;
    local.jawmeshPath = currentExecutablePath();
    local.maxJobs = args.jobs > 0 ? args.jobs : cores;
    // Threads split the cores among the tasks that can run together, unless --threads says otherwise.
    local.threadsPerTask = global.threads > 0 ? global.threads : std::max(1, cores / std::max(1, std::min(local.maxJobs, pending)));
    const std::uint64_t available = availableMemoryBytes();
    local.memoryBudgetBytes = args.memoryGb > 0 ? static_cast<std::uint64_t>(args.memoryGb * 1e9)
                              : available > 0   ? static_cast<std::uint64_t>(kMemoryBudgetShare * static_cast<double>(available))
                                                : std::numeric_limits<std::uint64_t>::max();
    Progress& progress = terminalProgress(global);
    local.cancelled = [&progress] { return progress.cancelled(); };
    int done = static_cast<int>(m.tasks.size()) - pending;
    const int total = static_cast<int>(m.tasks.size());
    if (!global.quiet)
        std::fprintf(stderr, "batch: %d tasks, %d to run (up to %d at once, %d threads each, memory budget %.1f GB)\n",
                     total, pending, local.maxJobs, local.threadsPerTask,
                     static_cast<double>(local.memoryBudgetBytes) / 1e9);
    local.taskFinished = [&](const TaskRecord& r) {
        if (global.quiet) return;
        if (r.status == TaskStatus::Pending) {
            std::fprintf(stderr, "batch: %s interrupted\n", taskName(r.task).c_str());
            return;
        }
        ++done;
        std::fprintf(stderr, "[%d/%d] %s: %s, %.1f s, %.0f MB%s%s\n", done, total, taskName(r.task).c_str(),
                     statusName(r.status).c_str(), r.seconds, static_cast<double>(r.peakMemoryBytes) / 1e6,
                     r.error.empty() ? "" : ": ", r.error.c_str());
    };
    local.warn = [&](const std::string& w) {
        if (!global.quiet) std::fprintf(stderr, "batch: warning: %s\n", w.c_str());
    };
    runLocalBatch(m, out, local);
    if (progress.cancelled()) {
        std::fprintf(stderr, "batch: interrupted; finished tasks are kept, rerun the same command to do the rest\n");
        throw Cancelled();
    }
    finish(m, out, global);
}

/// Runs `sbatch --parsable script` and returns the job id.
std::string submit(const std::string& script) {
    const std::string command = "sbatch --parsable " + shellQuote(script) + " 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) throw Error(script, "cannot run sbatch");
    std::string output;
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
    const int status = ::pclose(pipe);
    while (!output.empty() && (output.back() == '\n' || output.back() == '\r')) output.pop_back();
    if (status != 0) throw Error(script, "sbatch failed: " + output);
    return output.substr(0, output.find(';'));  // "<id>;<cluster>" on federated clusters
}

void prepareSlurm(const BatchArgs& args, const GlobalOptions& global) {
    const std::string out = absolute(args.outDir);
    checkInputs(args, out);
    FolderLock lock(out);
    BatchManifest m = prepare(args, out);
    std::vector<std::size_t> indices;
    std::uint64_t largestEstimate = 0;
    for (std::size_t i = 0; i < m.tasks.size(); ++i) {
        TaskRecord& r = m.tasks[i];
        if (r.status != TaskStatus::Pending) continue;
        indices.push_back(i);
        largestEstimate = std::max(largestEstimate, r.estimatedMemoryBytes);
        removeStalePartials(out, r.task);
        std::error_code ec;
        fs::remove(taskResultPath(out, r.task), ec);
    }
    if (indices.empty()) {
        if (!global.quiet) std::fprintf(stderr, "batch: nothing to submit, no task is waiting\n");
        finish(m, out, global);
        return;
    }
    // Slurm opens each task's log before the task starts: the folder must exist.
    std::error_code ec;
    fs::create_directories(out + "/logs", ec);
    if (ec) throw Error(out + "/logs", "cannot create log folder: " + ec.message());
    SlurmOptions slurm = args.slurmOptions;
    if (slurm.mem.empty()) slurm.mem = slurmMemory(largestEstimate);
    const std::string script = sbatchPath(out);
    writeFileAtomically(script, [&](std::ostream& o) { o << sbatchScript(slurm, currentExecutablePath(), out, indices); },
                        false);
    const std::string jobs = std::to_string(indices.size()) + " array task(s) (" + arraySpec(indices) + ")";
    if (!args.submit) {
        std::printf("wrote %s: %s; submit with `sbatch %s`, then collect with `jawmesh batch --status %s`\n",
                    script.c_str(), jobs.c_str(), script.c_str(), out.c_str());
        return;
    }
    m.slurmJobId = submit(script);
    for (std::size_t i : indices) m.tasks[i].log = "logs/slurm-" + m.slurmJobId + "_" + std::to_string(i) + ".log";
    writeManifest(m, out);
    std::printf("submitted job %s: %s; collect with `jawmesh batch --status %s`\n", m.slurmJobId.c_str(), jobs.c_str(),
                out.c_str());
}

void collectStatus(const std::string& dir, const GlobalOptions& global) {
    const std::string out = absolute(dir);
    FolderLock lock(out);
    BatchManifest m = readManifest(out);
    for (std::size_t i = 0; i < m.tasks.size(); ++i) {
        TaskRecord& r = m.tasks[i];
        r = collectTaskStatus(r, out, m.optionsHash, "no result yet (not finished, or killed: see " + r.log + ")");
    }
    writeManifest(m, out);
    finish(m, out, global);
}

void runBatch(const BatchArgs& args, const GlobalOptions& global) {
    if (!args.statusDir.empty()) return collectStatus(args.statusDir, global);
    if (args.outDir.empty()) throw Error("batch: -o <out> is required");
    if (args.arrayTask >= 0) return runBatchTask(absolute(args.outDir), static_cast<std::size_t>(args.arrayTask),
                                                 terminalProgress(global));
    if (args.dataset.empty()) throw Error("batch: the dataset folder is required");
    if (args.slurm) return prepareSlurm(args, global);
    if (args.submit) throw Error("batch: --submit needs --slurm");
    runLocal(args, global);
}

void addBatchCommand(CLI::App& app, GlobalOptions& global) {
    auto args = std::make_shared<BatchArgs>();
    auto* cmd = app.add_subcommand(
        "batch", "Every case and jaw of a dataset (<dataset>/<case>/input/<jaw>/...) -> <out>/<case>/<jaw>/, resumable; "
                 "locally or as a Slurm job array; manifest.json and summary.csv in <out>");
    cmd->add_option("dataset", args->dataset, "Dataset folder: one case folder per patient")
        ->check(CLI::ExistingDirectory);
    cmd->add_option("-o,--output", args->outDir, "Output folder (also where the manifest lives)");
    cmd->add_option("--config", args->config, "JSON file of run options (keys as recorded in run.json)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--edits", args->edits, "JSON file of what-if edits applied to every case (see `jawmesh run --edits`)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--jobs", args->jobs, "Cases at once, at most (0: as many as cores); fewer when memory is short")
        ->check(nonNegativeNumber());
    cmd->add_option("--memory-gb", args->memoryGb, "Memory budget for the cases at once, GB (default: 90% of the available memory)")
        ->default_str("")
        ->check(positiveNumber());
    auto* slurm = cmd->add_flag("--slurm", args->slurm, "Write a Slurm job-array script (<out>/slurm/batch.sbatch)");
    cmd->add_flag("--submit", args->submit, "With --slurm: submit it with sbatch");
    cmd->add_option("--partition", args->slurmOptions.partition, "Slurm partition")->needs(slurm);
    cmd->add_option("--time", args->slurmOptions.time, "Slurm time limit per task, e.g. 2:00:00")->needs(slurm);
    cmd->add_option("--mem", args->slurmOptions.mem, "Slurm memory per task, e.g. 8G (default: the largest estimate)")
        ->needs(slurm);
    cmd->add_option("--cpus", args->slurmOptions.cpus, "Slurm CPUs per task (also its threads)")
        ->check(positiveNumber())
        ->capture_default_str()
        ->needs(slurm);
    cmd->add_option("--array-task", args->arrayTask, "Run task <i> of <out>/manifest.json (what each array task runs)")
        ->default_str("")
        ->check(nonNegativeNumber());
    cmd->add_option("--status", args->statusDir, "Collect the results of a batch output folder (e.g. after Slurm)")
        ->check(CLI::ExistingDirectory);
    cmd->callback([args, &global] { runBatch(*args, global); });
}

}  // namespace
JAWMESH_COMMAND(70, addBatchCommand);
}  // namespace jawmesh
