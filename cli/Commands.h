// Each subcommand lives in its own cli/Cmd*.cpp and registers itself on the app here. The CLI only
// parses options and wires library stages; all work happens in the stage libraries.
#pragma once

#include <CLI/CLI.hpp>

namespace jawmesh {

/// Options every subcommand shares.
struct GlobalOptions {
    bool quiet = false;
    int threads = 0;  ///< 0 = all hardware threads
};

/// Exit codes: 0 success, 1 a stage failed or input was bad, 2 usage error (CLI11), 130 cancelled.
constexpr int kExitFailure = 1;
constexpr int kExitCancelled = 130;

void addPhantomCommand(CLI::App& app, GlobalOptions& global);
void addLevelsetCommand(CLI::App& app, GlobalOptions& global);

}  // namespace jawmesh
