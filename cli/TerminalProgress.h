// Progress on a terminal: "[mandible / carve] 42% 3.1 s" redrawn in place on a TTY, one line per
// finished top-level stage otherwise; silent with --quiet. Nested stages show as "outer / inner"
// with the innermost stage's percentage and the outer stage's elapsed time. Ctrl-C (or SIGTERM) sets a flag that
// library code polls, so a run stops at a safe point and writes no partial output.
#pragma once

#include "io/Progress.h"

#include <chrono>
#include <mutex>
#include <string>
#include <vector>

namespace jawmesh {

class TerminalProgress : public Progress {
public:
    explicit TerminalProgress(bool quiet);
    void begin(const std::string& stage) override;
    void update(double fraction) override;
    void end() override;
    bool cancelled() const override;

    /// Installs SIGINT and SIGTERM handlers that make cancelled() true (a second signal kills at once).
    static void installInterruptHandler();

private:
    using Clock = std::chrono::steady_clock;
    struct Stage {
        std::string name;
        Clock::time_point start;
    };
    void draw(double fraction, bool final);

    bool quiet_;
    bool tty_;
    std::mutex mutex_;
    std::vector<Stage> stack_;
    Clock::time_point lastDraw_;
    int lastPercent_ = -1;
};

}  // namespace jawmesh
