#include "cli/TerminalProgress.h"

#include <csignal>
#include <cstdio>
#include <unistd.h>

namespace jawmesh {
namespace {
std::atomic<int> gInterrupts{0};

extern "C" void onSigint(int) {
    if (gInterrupts.fetch_add(1) >= 1) {
        std::signal(SIGINT, SIG_DFL);
        std::raise(SIGINT);
    }
}
}  // namespace

TerminalProgress::TerminalProgress(bool quiet) : quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0) {}

void TerminalProgress::installInterruptHandler() { std::signal(SIGINT, onSigint); }

bool TerminalProgress::cancelled() const { return gInterrupts.load() > 0; }

void TerminalProgress::begin(const std::string& stage) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++depth_;
    if (depth_ > 1) return;  // nested stages report under the outer one
    stage_ = stage;
    stageStart_ = Clock::now();
    lastDraw_ = Clock::time_point{};
    lastPercent_ = -1;
    draw(0.0, false);
}

void TerminalProgress::update(double fraction) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (depth_ != 1) return;
    draw(fraction, false);
}

void TerminalProgress::end() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (depth_ == 1) draw(1.0, true);
    if (depth_ > 0) --depth_;
}

void TerminalProgress::draw(double fraction, bool final) {
    if (quiet_) return;
    const auto now = Clock::now();
    const int percent = static_cast<int>(fraction * 100.0 + 0.5);
    if (!final) {
        if (!tty_) return;  // logs get one line per stage, not a stream of updates
        if (percent == lastPercent_ && now - lastDraw_ < std::chrono::milliseconds(250)) return;
    }
    lastPercent_ = percent;
    lastDraw_ = now;
    const double seconds = std::chrono::duration<double>(now - stageStart_).count();
    if (tty_)
        std::fprintf(stderr, "\r\033[K[%s] %3d%% %.1f s%s", stage_.c_str(), percent, seconds, final ? "\n" : "");
    else
        std::fprintf(stderr, "[%s] done in %.1f s\n", stage_.c_str(), seconds);
    std::fflush(stderr);
}

}  // namespace jawmesh
