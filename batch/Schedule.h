// Which waiting task a batch starts next: the first (in task order) whose memory estimate fits
// beside the running ones, with a cap on how many run at once.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace jawmesh {

/// Index into waitingEstimates (bytes, in task order) of the task to start now, or nothing when
/// none may start: `running` tasks already use runningBytes of their estimates; a task may start
/// when running < maxJobs and runningBytes + its estimate <= budgetBytes. When nothing runs, the
/// first waiting task starts even if it exceeds the budget (it is the best the machine can do; the
/// caller warns). Pure function.
std::optional<std::size_t> nextTaskToStart(const std::vector<std::uint64_t>& waitingEstimates, int running,
                                           std::uint64_t runningBytes, int maxJobs, std::uint64_t budgetBytes);

}  // namespace jawmesh
