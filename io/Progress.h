// Progress and cancellation for long operations, in the spirit of OpenVDB's interrupters:
// library code reports stage names and fractions and never prints; the CLI decides what to show.
#pragma once

#include "io/Error.h"

#include <string>

namespace jawmesh {

class Progress {
public:
    virtual ~Progress() = default;
    /// A named stage starts (e.g. "levelset bone").
    virtual void begin(const std::string& stage) {}
    /// Fraction of the current stage done, in [0, 1]. Must be cheap; may be called from any thread.
    virtual void update(double fraction) {}
    /// The current stage ended.
    virtual void end() {}
    /// True once the user asked to stop; long loops poll it through checkCancelled().
    virtual bool cancelled() const { return false; }

    /// Throws Cancelled when cancelled(): call at safe points in long loops.
    void checkCancelled() const {
        if (cancelled()) throw Cancelled();
    }
};

/// The do-nothing default for callers that do not care.
inline Progress& noProgress() {
    static Progress none;
    return none;
}

/// What a step running beside others reports: only whether to stop (their stages and fractions
/// would interleave on one bar; the caller reports the steps done).
class CancelOnlyProgress : public Progress {
public:
    explicit CancelOnlyProgress(const Progress& p) : p_(p) {}
    bool cancelled() const override { return p_.cancelled(); }

private:
    const Progress& p_;
};

/// begin() on construction, end() on destruction, so early returns and throws stay balanced.
class ProgressStage {
public:
    ProgressStage(Progress& p, const std::string& stage) : p_(p) { p_.begin(stage); }
    ~ProgressStage() { p_.end(); }
    ProgressStage(const ProgressStage&) = delete;
    ProgressStage& operator=(const ProgressStage&) = delete;
    void update(double fraction) { p_.update(fraction); }

private:
    Progress& p_;
};

}  // namespace jawmesh
