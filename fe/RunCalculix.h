// Running the CalculiX solver (ccx, Debian package calculix-ccx) on a deck written by
// writeCalculixDeck, and summarising what it computed from its own output files.
#pragma once

#include "fe/Scenario.h"
#include "io/TetMesh.h"

#include <nlohmann/json.hpp>

#include <string>

namespace jawmesh {

/// Full path of `ccx` on PATH, or "" when CalculiX is not installed.
std::string findCalculix();

struct CalculixRun {
    std::string status;      ///< "completed" | "failed" | "not installed"
    int exitCode = -1;
    double seconds = 0;      ///< wall time of the solver
    std::string message;     ///< first *ERROR line of the log, or why it did not run
    std::string logPath;     ///< <deck folder>/<job>.log (ccx's stdout and stderr)
};

/// Runs `ccx -i <job>` in the folder of `inpPath` (job = file name without .inp), with
/// OMP_NUM_THREADS = threads, output to <job>.log. "completed" means ccx exited 0, printed
/// "Job finished" and its .dat reached step time 1 (the full load). Never throws for a solver
/// failure (that is a status); throws Error only when the deck does not exist.
CalculixRun runCalculix(const std::string& inpPath, int threads = 1);

/// Summary of a run, read from ccx's .dat and .frd next to `inpPath`:
/// {"solver": "calculix", "status", "seconds", "message",
///  "teeth": [{"unn", "load_node", "displacement_mm": [x, y, z], "magnitude_mm",
///             "along_force_mm" (displacement . unit force; > 0 = moved lingually),
///             "tooth_max_displacement_mm" (largest over the tooth's nodes; only when `mesh` is given),
///             "socket_mean_displacement_mm": [x, y, z] (mean over the nodes its PDL shares with the
///             bone) and "tooth_max_displacement_in_socket_mm" (largest over the tooth's nodes of
///             the displacement minus that mean: how far the tooth moves in its bone; with `mesh`)}],
///  "regions": {"tooth_24": {"elements", "max_von_mises_mpa", "median_von_mises_mpa",
///              "p9999_von_mises_mpa"}, ...},
///  "pdl": the same figures over the elements of every PDL together, plus "p9999_over_median",
///  "max_displacement_mm": largest nodal displacement of the .frd}.
/// Element von Mises stress is the largest over the element's integration points.
/// Without a completed run only solver, status, seconds and message are filled.
/// Throws Error when a completed run's output files are missing or malformed.
nlohmann::json calculixSummary(const FeScenario& scenario, const CalculixRun& run, const std::string& inpPath,
                               const TetMesh* mesh = nullptr);

}  // namespace jawmesh
