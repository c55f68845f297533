// Bash completion for the jawmesh command line, generated from the parser itself so that it
// never falls behind the options (`jawmesh completion bash`).
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace jawmesh {

/// A bash script defining `_jawmesh` and registering it with `complete`: subcommand names first,
/// then each subcommand's options (the global ones included); file names elsewhere.
std::string bashCompletion(const CLI::App& root);

}  // namespace jawmesh
