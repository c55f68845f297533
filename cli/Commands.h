// Each subcommand lives in its own cli/Cmd*.cpp and registers itself with JAWMESH_COMMAND, so
// adding a command never touches another file. The CLI only parses options and wires library
// stages; all work happens in the stage libraries.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace jawmesh {

class Progress;

/// Options every subcommand shares.
struct GlobalOptions {
    bool quiet = false;
    int threads = 0;  ///< 0 = all hardware threads
};

/// Exit codes: 0 success, 1 a stage failed or input was bad, 2 usage error, 130 cancelled.
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;
constexpr int kExitCancelled = 130;

using CommandAdder = void (*)(CLI::App& app, GlobalOptions& global);

/// Registers a subcommand; `order` sorts the --help listing (pipeline order).
struct CommandRegistration {
    CommandRegistration(int order, CommandAdder add);
};

/// Adds every registered subcommand to app.
void addRegisteredCommands(CLI::App& app, GlobalOptions& global);

/// The terminal progress reporter of this process (quiet or not per the global options).
Progress& terminalProgress(const GlobalOptions& global);

}  // namespace jawmesh

#define JAWMESH_COMMAND(order, fn) \
    static const ::jawmesh::CommandRegistration jawmeshCommandRegistration_##fn(order, fn)
