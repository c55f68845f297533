// fork/exec for programs, fork/pipe for functions; both reaped with wait4 for the child's rusage.
#include "io/ChildProcess.h"

#include "io/Error.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace jawmesh {
namespace {

ChildExit childExit(pid_t pid, int status, const struct rusage& usage) {
    ChildExit e;
    e.pid = pid;
    if (WIFEXITED(status)) e.exitCode = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) e.signal = WTERMSIG(status);
    e.peakMemoryBytes = static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;  // Linux reports KiB
    return e;
}

// runForked's child ends what `work` sent with a trailer the parent reads from the end: one status
// byte, kReturned, or kThrew after the exception's message and its length (8 bytes).
constexpr char kReturned = 0;
constexpr char kThrew = 1;

void sendThrown(ParentPipe& pipe, const std::string& message) {
    const std::uint64_t n = message.size();
    sendToParent(pipe, message.data(), message.size());
    sendToParent(pipe, &n, 1);
    sendToParent(pipe, &kThrew, 1);
}

[[noreturn]] void runChild(const std::function<void(ParentPipe&)>& work, ParentPipe pipe) {
    try {
        work(pipe);
        sendToParent(pipe, &kReturned, 1);
    } catch (const std::exception& e) {
        sendThrown(pipe, e.what());
    } catch (...) {
        sendThrown(pipe, "unknown exception");
    }
    ::close(pipe.fd);
    ::_exit(0);  // no destructors or atexit handlers of the parent's state
}

/// Reads the whole of what the child wrote (until it closes its end).
std::vector<char> readAll(int fd) {
    std::vector<char> out;
    char buf[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        out.insert(out.end(), buf, buf + n);
    }
    return out;
}

/// Takes the trailer (runChild) off r.bytes and says how the function ended.
void readTrailer(ForkedResult& r) {
    if (r.exit.exitCode != 0 || r.bytes.empty()) return;
    const char status = r.bytes.back();
    r.bytes.pop_back();
    if (status == kReturned) {
        r.returned = true;
        return;
    }
    std::uint64_t n = 0;
    if (status != kThrew || r.bytes.size() < sizeof n) return;
    std::memcpy(&n, r.bytes.data() + r.bytes.size() - sizeof n, sizeof n);
    const std::size_t messageEnd = r.bytes.size() - sizeof n;
    if (n > messageEnd) return;
    r.thrown = std::string(r.bytes.data() + (messageEnd - n), n);
    r.bytes.resize(messageEnd - n);
}

}  // namespace

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
    return childExit(pid, status, usage);
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

void sendBytesToParent(ParentPipe& pipe, const void* data, std::size_t bytes) {
    const char* p = static_cast<const char*>(data);
    while (bytes > 0) {
        const ssize_t n = ::write(pipe.fd, p, bytes);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) ::_exit(kSendFailedExit);
        p += n;
        bytes -= std::size_t(n);
    }
}

bool takeBytes(const std::vector<char>& bytes, std::size_t& at, void* data, std::size_t size) {
    if (at + size > bytes.size()) return false;
    std::memcpy(data, bytes.data() + at, size);
    at += size;
    return true;
}

namespace {

/// Waits for child `pid` to end and says how it ended.
ChildExit reap(pid_t pid) {
    int status = 0;
    struct rusage usage {};
    while (::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
    }
    return childExit(pid, status, usage);
}

}  // namespace

ForkedChild::ForkedChild(ForkedChild&& other) noexcept : pid(other.pid), fd(other.fd) {
    other.pid = -1;
    other.fd = -1;
}

ForkedChild::~ForkedChild() {
    if (pid < 0) return;
    ::kill(pid, SIGKILL);
    ::close(fd);
    reap(pid);
}

ForkedChild startForked(const std::function<void(ParentPipe&)>& work) {
    int fds[2];
    if (::pipe(fds) != 0) throw Error(std::string("cannot create a pipe for a child process (") + std::strerror(errno) + ")");
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0) {
        const int err = errno;
        ::close(fds[0]);
        ::close(fds[1]);
        throw Error(std::string("cannot fork a child process (") + std::strerror(err) + ")");
    }
    if (pid == 0) {
        ::close(fds[0]);
        runChild(work, ParentPipe{fds[1]});
    }
    ::close(fds[1]);
    ForkedChild child;
    child.pid = pid;
    child.fd = fds[0];
    return child;
}

ForkedResult finishForked(ForkedChild& child) {
    ForkedResult r;
    r.bytes = readAll(child.fd);
    ::close(child.fd);
    r.exit = reap(child.pid);
    child.pid = -1;
    child.fd = -1;
    readTrailer(r);
    return r;
}

ForkedResult runForked(const std::function<void(ParentPipe&)>& work) {
    ForkedChild child = startForked(work);
    return finishForked(child);
}

}  // namespace jawmesh
