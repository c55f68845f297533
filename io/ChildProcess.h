// Child processes, for work that must not take this process down with it: batch tasks run the
// jawmesh binary itself (startChild, reapFinishedChild), and a library call that may abort (TetGen)
// runs in a fork that sends its result back through a pipe (runForked). Either way a crash or an
// out-of-memory kill stays in the child, and its peak memory is measured by the kernel (wait4's
// rusage) even when it dies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace jawmesh {

/// How a child process ended.
struct ChildExit {
    int pid = 0;
    int exitCode = -1;                 ///< when it exited normally, else -1
    int signal = 0;                    ///< the signal that killed it, else 0
    std::uint64_t peakMemoryBytes = 0; ///< its peak resident set size (ru_maxrss)
};

/// "exit code 3" / "killed by signal 9 (Killed)".
std::string describeExit(const ChildExit& exit);

// ---- programs (batch tasks) ----

/// Starts argv[0] (a path) with argv, stdin from /dev/null, stdout and stderr appended to logPath
/// (created with its folder), in its own process group (a terminal's Ctrl-C reaches only this
/// process, which stops its children with interruptChild). The child is killed (SIGKILL) if this
/// process dies first, so no orphan keeps writing after a killed batch. Returns the child's pid.
/// Throws Error when the log cannot be opened or fork fails; a failing exec shows as exit code 127.
int startChild(const std::vector<std::string>& argv, const std::string& logPath);

/// Reaps one finished child (any child of this process) without blocking; nothing when no child has finished.
std::optional<ChildExit> reapFinishedChild();

/// Sends SIGINT (the cooperative stop: the child's pipeline cancels at a safe point).
void interruptChild(int pid);

/// This executable's absolute path (/proc/self/exe). Throws Error when unavailable.
std::string currentExecutablePath();

// ---- functions (runForked) ----

/// The child's end of runForked's pipe: what is sent through it is the parent's ForkedResult::bytes.
struct ParentPipe {
    int fd = -1;
};

/// Sends `count` values of a trivially copyable type (Vec3 included) to the parent, as they lie in
/// memory. In runForked's child only: a write that fails ends the child (exit code kSendFailedExit).
void sendBytesToParent(ParentPipe& pipe, const void* data, std::size_t bytes);
template <class T>
void sendToParent(ParentPipe& pipe, const T* data, std::size_t count) {
    sendBytesToParent(pipe, data, count * sizeof(T));
}
constexpr int kSendFailedExit = 3;

/// Copies `count` values of T from `bytes` at `at` (advanced past them) into `data`, the reverse
/// of sendToParent. Returns false, copying nothing, when fewer bytes are left.
bool takeBytes(const std::vector<char>& bytes, std::size_t& at, void* data, std::size_t size);
template <class T>
bool takeFromChild(const std::vector<char>& bytes, std::size_t& at, T* data, std::size_t count) {
    return takeBytes(bytes, at, data, count * sizeof(T));
}

/// What runForked's child sent and how it ended.
struct ForkedResult {
    ChildExit exit;
    /// What the function sent, once it returned (complete) or threw (what it sent before that).
    std::vector<char> bytes;
    bool returned = false;             ///< the function returned and its child exited with code 0
    std::optional<std::string> thrown; ///< what() of the exception it threw ("unknown exception" for a non-std one)
};

/// Runs `work` in a forked child of this process and returns what it sent through its pipe (read
/// to the end, then the child is reaped). For calls that may abort or crash instead of throwing:
/// the child is a copy of this process, so `work` may read anything the parent had, and whatever
/// it changes stays in the child. Only the calling thread is copied by fork, so `work` must not
/// need a thread pool (TBB's included) or locks other threads may have held. The child ends with
/// _exit (no destructors or atexit handlers of the parent's state). Standard streams are flushed
/// before the fork, so no buffered output is written twice.
/// Throws Error when the pipe or the fork cannot be made; a child that dies is no exception but
/// a ForkedResult with exit.signal set (and returned false).
ForkedResult runForked(const std::function<void(ParentPipe&)>& work);

/// runForked in two halves, so that this process can work while the child does: startForked forks
/// and returns at once, finishForked reads what the child sent and reaps it. A child never
/// finished is killed and reaped when its ForkedChild goes (the parent threw in between).
/// Fork only where no other thread of this process may hold a lock the child needs: the
/// sanitizers' allocator has no fork handler, so a child copied while another thread is inside
/// malloc waits for that lock forever.
struct ForkedChild {
    int pid = -1; ///< -1 once finished
    int fd = -1;  ///< the parent's end of the pipe
    ForkedChild() = default;
    ForkedChild(ForkedChild&& other) noexcept;
    ForkedChild(const ForkedChild&) = delete;
    ForkedChild& operator=(const ForkedChild&) = delete;
    ForkedChild& operator=(ForkedChild&&) = delete;
    ~ForkedChild();
};
ForkedChild startForked(const std::function<void(ParentPipe&)>& work);
ForkedResult finishForked(ForkedChild& child);

}  // namespace jawmesh
