#include "batch/ChildProcess.h"

#include "io/Error.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace jawmesh {

int startChild(const std::vector<std::string>& argv, const std::string& logPath) {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(logPath).parent_path(), ec);
    const int log = ::open(logPath.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (log < 0) throw Error(logPath, std::string("cannot open log: ") + std::strerror(errno));
    // Everything the child needs is prepared before fork: between fork and exec only
    // async-signal-safe calls are allowed (the parent may have TBB threads).
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(log);
        throw Error(std::string("cannot start a task process: ") + std::strerror(errno));
    }
    if (pid == 0) {
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(126);  // the parent died before prctl took effect
        // Own process group: a terminal's Ctrl-C reaches only the batch, which then stops each
        // task once (interruptChild); a second SIGINT would kill a task instead of cancelling it.
        ::setpgid(0, 0);
        const int devNull = ::open("/dev/null", O_RDONLY);
        if (devNull >= 0) ::dup2(devNull, STDIN_FILENO);
        ::dup2(log, STDOUT_FILENO);
        ::dup2(log, STDERR_FILENO);
        ::execv(args[0], args.data());
        ::_exit(127);
    }
    ::close(log);
    return pid;
}

std::optional<ChildExit> reapFinishedChild() {
    int status = 0;
    struct rusage usage {};
    const pid_t pid = ::wait4(-1, &status, WNOHANG, &usage);
    if (pid <= 0) return std::nullopt;
    ChildExit e;
    e.pid = pid;
    if (WIFEXITED(status)) e.exitCode = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
    e.peakMemoryBytes = static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;  // Linux reports KiB
    return e;
}

void interruptChild(int pid) { ::kill(pid, SIGINT); }

std::string describeExit(const ChildExit& e) {
    if (e.signal != 0) return "killed by signal " + std::to_string(e.signal) + " (" + ::strsignal(e.signal) + ")";
    return "exit code " + std::to_string(e.exitCode);
}

std::string currentExecutablePath() {
    std::error_code ec;
    const auto path = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throw Error("/proc/self/exe", "cannot find the jawmesh executable: " + ec.message());
    return path.string();
}

}  // namespace jawmesh
