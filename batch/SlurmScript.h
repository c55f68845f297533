// The Slurm side of a batch: an sbatch job-array script with one array task per (case, jaw) still
// to do; every array task runs `jawmesh batch --array-task <index> -o <out>`, which reads the
// manifest, so the script itself holds no case list.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace jawmesh {

struct SlurmOptions {
    std::string partition;  ///< --partition; empty: the cluster's default
    std::string time;       ///< --time, e.g. "2:00:00"; empty: the partition's default
    std::string mem;        ///< --mem, e.g. "8G"; empty: the caller fills it from the memory estimate
    int cpus = 2;           ///< --cpus-per-task, also the task's --threads
};

/// s single-quoted for sh (any path is then safe in a script or a command line).
std::string shellQuote(const std::string& s);

/// "0-3,5,7-8" for sorted, distinct indices (Slurm's --array syntax). Empty for none.
std::string arraySpec(const std::vector<std::size_t>& indices);

/// Memory in Slurm's --mem syntax, rounded up to whole gigabytes ("3G"), at least 1G.
std::string slurmMemory(std::uint64_t bytes);

/// The sbatch script text. jawmeshPath and outDir must be absolute (tasks run on other nodes, in
/// other folders); logs go to <outDir>/logs/slurm-<job>_<index>.log. indices must not be empty.
std::string sbatchScript(const SlurmOptions& options, const std::string& jawmeshPath, const std::string& outDir,
                         const std::vector<std::size_t>& indices);

}  // namespace jawmesh
