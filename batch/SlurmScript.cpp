// Implements batch/SlurmScript.h; what it computes, its rules and its contract are documented there.
#include "batch/SlurmScript.h"

#include <cstdint>

namespace jawmesh {
std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string arraySpec(const std::vector<std::size_t>& indices) {
    std::string spec;
    for (std::size_t i = 0; i < indices.size();) {
        std::size_t j = i;
        while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
        if (!spec.empty()) spec += ",";
        spec += std::to_string(indices[i]);
        if (j > i) spec += "-" + std::to_string(indices[j]);
        i = j + 1;
    }
    return spec;
}

std::string slurmMemory(std::uint64_t bytes) {
    const std::uint64_t gib = 1ull << 30;
    const std::uint64_t g = bytes == 0 ? 1 : (bytes + gib - 1) / gib;
    return std::to_string(g) + "G";
}

std::string sbatchScript(const SlurmOptions& o, const std::string& jawmeshPath, const std::string& outDir,
                         const std::vector<std::size_t>& indices) {
    std::string s = "#!/bin/sh\n";
    s += "# Written by `jawmesh batch --slurm`: one array task per (case, jaw) of " + outDir + "/manifest.json.\n";
    s += "# Submit with `sbatch " + outDir + "/slurm/batch.sbatch`; collect with `jawmesh batch --status " + outDir + "`.\n";
    s += "#SBATCH --job-name=jawmesh-batch\n";
    s += "#SBATCH --array=" + arraySpec(indices) + "\n";
    s += "#SBATCH --cpus-per-task=" + std::to_string(o.cpus) + "\n";
    if (!o.mem.empty()) s += "#SBATCH --mem=" + o.mem + "\n";
    if (!o.time.empty()) s += "#SBATCH --time=" + o.time + "\n";
    if (!o.partition.empty()) s += "#SBATCH --partition=" + o.partition + "\n";
    s += "#SBATCH --output=" + outDir + "/logs/slurm-%A_%a.log\n";
    s += "exec " + shellQuote(jawmeshPath) + " --threads \"${SLURM_CPUS_PER_TASK:-" + std::to_string(o.cpus) +
         "}\" batch --array-task \"$SLURM_ARRAY_TASK_ID\" -o " + shellQuote(outDir) + "\n";
    return s;
}

}  // namespace jawmesh
