// Batch tasks run in child processes (the jawmesh binary itself), so a crash or an out-of-memory
// kill of one case cannot take the batch down, and each case's peak memory is measured by the
// kernel (wait4's rusage) even when the case dies.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace jawmesh {

/// Starts argv[0] (a path) with argv, stdin from /dev/null, stdout and stderr appended to logPath
/// (created with its folder), in its own process group (a terminal's Ctrl-C reaches only this
/// process, which stops its children with interruptChild). The child is killed (SIGKILL) if this
/// process dies first, so no orphan keeps writing after a killed batch. Returns the child's pid.
/// Throws Error when the log cannot be opened or fork fails; a failing exec shows as exit code 127.
int startChild(const std::vector<std::string>& argv, const std::string& logPath);

struct ChildExit {
    int pid = 0;
    int exitCode = -1;                 ///< when it exited normally, else -1
    int signal = 0;                    ///< the signal that killed it, else 0
    std::uint64_t peakMemoryBytes = 0; ///< its peak resident set size (ru_maxrss)
};

/// Reaps one finished child without blocking; nothing when no child has finished.
std::optional<ChildExit> reapFinishedChild();

/// Sends SIGINT (the cooperative stop: the child's pipeline cancels at a safe point).
void interruptChild(int pid);

/// "exit code 3" / "killed by signal 9 (Killed)".
std::string describeExit(const ChildExit& exit);

/// This executable's absolute path (/proc/self/exe). Throws Error when unavailable.
std::string currentExecutablePath();

}  // namespace jawmesh
