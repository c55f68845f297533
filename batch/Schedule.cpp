// Implements batch/Schedule.h; what it computes, its rules and its contract are documented there.
#include "batch/Schedule.h"

namespace jawmesh {

std::optional<std::size_t> nextTaskToStart(const std::vector<std::uint64_t>& waitingEstimates, int running,
                                           std::uint64_t runningBytes, int maxJobs, std::uint64_t budgetBytes) {
    if (waitingEstimates.empty() || running >= maxJobs) return std::nullopt;
    if (running == 0) return 0;
    for (std::size_t i = 0; i < waitingEstimates.size(); ++i)
        if (runningBytes + waitingEstimates[i] <= budgetBytes) return i;
    return std::nullopt;
}

}  // namespace jawmesh
