// Implements cli/TerminalProgress.h; what it computes, its rules and its contract are documented there.
#include "cli/TerminalProgress.h"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <unistd.h>

namespace jawmesh {
namespace {
std::atomic<int> gInterrupts{0};

// SIGTERM (kill, Slurm's scancel, a container stop) is a request to stop like Ctrl-C: the run
// stops at its next safe point and removes its staging folder.
extern "C" void onInterrupt(int signal) {
    if (gInterrupts.fetch_add(1) >= 1) {
        std::signal(signal, SIG_DFL);
        std::raise(signal);
    }
}
}  // namespace

TerminalProgress::TerminalProgress(bool quiet) : quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0) {}

void TerminalProgress::installInterruptHandler() {
    std::signal(SIGINT, onInterrupt);
    std::signal(SIGTERM, onInterrupt);
}

bool TerminalProgress::cancelled() const { return gInterrupts.load() > 0; }

void TerminalProgress::begin(const std::string& stage) {
    std::lock_guard<std::mutex> lock(mutex_);
    stack_.push_back({stage, Clock::now()});
    lastPercent_ = -1;
    draw(0.0, false);
}

void TerminalProgress::update(double fraction) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!stack_.empty()) draw(fraction, false);
}

void TerminalProgress::end() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stack_.empty()) return;
    if (stack_.size() == 1) draw(1.0, true);
    stack_.pop_back();
}

void TerminalProgress::draw(double fraction, bool final) {
    if (quiet_) return;
    const auto now = Clock::now();
    const int percent = static_cast<int>(fraction * 100.0 + 0.5);
    if (!final) {
        if (!tty_) return;  // logs get one line per top-level stage, not a stream of updates
        if (percent == lastPercent_ && now - lastDraw_ < std::chrono::milliseconds(250)) return;
    }
    lastPercent_ = percent;
    lastDraw_ = now;
    std::string name;
    for (const Stage& s : stack_) name += (name.empty() ? "" : " / ") + s.name;
    const double seconds = std::chrono::duration<double>(now - stack_.front().start).count();
    if (tty_)
        std::fprintf(stderr, "\r\033[K[%s] %3d%% %.1f s%s", name.c_str(), percent, seconds, final ? "\n" : "");
    else
        std::fprintf(stderr, "[%s] done in %.1f s\n", name.c_str(), seconds);
    std::fflush(stderr);
}

}  // namespace jawmesh
