// Process resource figures for reports and benchmarks (run.json, --json outputs).
#pragma once

#include <chrono>
#include <cstdint>

namespace jawmesh {

/// Peak resident set size of this process so far, bytes (getrusage ru_maxrss); 0 if unavailable.
/// Cost: one system call.
std::uint64_t peakResidentMemoryBytes();

/// Wall seconds since `start` (steady clock): how every stage and command times itself.
inline double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// CPU time of this process so far (user + system, all threads), seconds; 0 if unavailable.
double processCpuSeconds();

/// Hands heap pages that are free but still resident back to the system (glibc's malloc_trim;
/// nothing elsewhere). Between stages: a stage frees millions of small blocks (grid leaves) whose
/// pages glibc keeps, while the next stage's large arrays are mapped afresh, so both would count
/// in the peak. Cost: a walk over the heap, milliseconds.
void returnFreedMemory();

}  // namespace jawmesh
