// Implements batch/RunLocal.h; what it computes, its rules and its contract are documented there.
#include "batch/RunLocal.h"

#include "batch/BatchLayout.h"
#include "batch/BatchPlan.h"
#include "batch/Schedule.h"
#include "io/ChildProcess.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <thread>

namespace jawmesh {
namespace {

using Clock = std::chrono::steady_clock;

struct Running {
    std::size_t task = 0;
    std::uint64_t estimateBytes = 0;
    Clock::time_point start;
};

constexpr int kExitCancelled = 130;  // as the jawmesh CLI reports a Ctrl-C

/// The record of a task whose process has ended.
TaskRecord finishedRecord(const BatchManifest& m, std::size_t index, const std::string& outDir, const ChildExit& exit,
                          double seconds) {
    const TaskRecord& planned = m.tasks[index];
    TaskRecord r = collectTaskStatus(planned, outDir, m.optionsHash, "");
    r.peakMemoryBytes = exit.peakMemoryBytes;
    if (r.status == TaskStatus::Failed) r.seconds = seconds;
    const bool interrupted = exit.exitCode == kExitCancelled || exit.signal == SIGINT;
    if (r.status == TaskStatus::Pending && !interrupted) {
        r.status = TaskStatus::Failed;
        r.seconds = seconds;
        r.error = (exit.signal ? "crashed: " : "ended without a result: ") + describeExit(exit) + "; see " + r.log;
    } else if (r.status == TaskStatus::Pending) {
        r.error = "interrupted";
    }
    return r;
}

}  // namespace

void runLocalBatch(BatchManifest& m, const std::string& outDir, const LocalBatchOptions& options) {
    std::vector<std::size_t> waiting;
    std::uint64_t largestEstimate = 0;
    for (std::size_t i = 0; i < m.tasks.size(); ++i) {
        if (m.tasks[i].status != TaskStatus::Pending) continue;
        waiting.push_back(i);
        largestEstimate = std::max(largestEstimate, m.tasks[i].estimatedMemoryBytes);
    }
    // A jaw whose surfaces could not be read has no estimate; assume the worst of the batch.
    auto estimateOf = [&](std::size_t i) {
        return m.tasks[i].estimatedMemoryBytes ? m.tasks[i].estimatedMemoryBytes : largestEstimate;
    };

    std::map<int, Running> running;  // by pid
    std::uint64_t runningBytes = 0;
    bool interrupted = false;
    while (!waiting.empty() || !running.empty()) {
        if (!interrupted && options.cancelled && options.cancelled()) {
            interrupted = true;
            waiting.clear();
            for (const auto& [pid, run] : running) interruptChild(pid);
        }
        for (;;) {
            std::vector<std::uint64_t> estimates;
            for (std::size_t i : waiting) estimates.push_back(estimateOf(i));
            const auto next = nextTaskToStart(estimates, static_cast<int>(running.size()), runningBytes, options.maxJobs,
                                              options.memoryBudgetBytes);
            if (!next) break;
            const std::size_t index = waiting[*next];
            waiting.erase(waiting.begin() + static_cast<std::ptrdiff_t>(*next));
            const DatasetTask& task = m.tasks[index].task;
            if (estimates[*next] > options.memoryBudgetBytes && options.warn)
                options.warn(taskName(task) + ": estimated " + std::to_string(estimates[*next] / 1000000) +
                             " MB exceeds the memory budget of " + std::to_string(options.memoryBudgetBytes / 1000000) +
                             " MB; running it alone");
            removeStalePartials(outDir, task);
            std::error_code ec;
            std::filesystem::remove(taskResultPath(outDir, task), ec);
            std::filesystem::remove(taskLogPath(outDir, task), ec);
            const int pid = startChild({options.jawmeshPath, "--threads", std::to_string(options.threadsPerTask), "batch",
                                        "--array-task", std::to_string(index), "-o", outDir},
                                       taskLogPath(outDir, task));
            running[pid] = {index, estimates[*next], Clock::now()};
            runningBytes += estimates[*next];
        }
        const std::optional<ChildExit> exit = reapFinishedChild();
        if (!exit) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            continue;
        }
        const auto it = running.find(exit->pid);
        if (it == running.end()) continue;  // not one of ours
        const Running run = it->second;
        running.erase(it);
        runningBytes -= run.estimateBytes;
        const double seconds = std::chrono::duration<double>(Clock::now() - run.start).count();
        m.tasks[run.task] = finishedRecord(m, run.task, outDir, *exit, seconds);
        writeManifest(m, outDir);
        if (options.taskFinished) options.taskFinished(m.tasks[run.task]);
    }
}

}  // namespace jawmesh
