// Process resource figures for reports and benchmarks (run.json, --json outputs).
#pragma once

#include <cstdint>

namespace jawmesh {

/// Peak resident set size of this process so far, bytes (getrusage ru_maxrss); 0 if unavailable.
/// Cost: one system call.
std::uint64_t peakResidentMemoryBytes();

}  // namespace jawmesh
