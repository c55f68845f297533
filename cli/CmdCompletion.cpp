// `jawmesh completion bash`: prints the bash completion script (cli/BashCompletion.h).
#include "cli/BashCompletion.h"
#include "cli/Commands.h"

#include <cstdio>
#include <memory>
#include <string>

namespace jawmesh {
namespace {

void addCompletionCommand(CLI::App& app, GlobalOptions&) {
    auto shell = std::make_shared<std::string>();
    auto* cmd = app.add_subcommand("completion", "Print a shell completion script: source <(jawmesh completion bash)");
    cmd->add_option("shell", *shell, "Shell")->required()->check(CLI::IsMember({"bash"}));
    const CLI::App* root = &app;
    cmd->callback([root, shell] { std::fputs(bashCompletion(*root).c_str(), stdout); });
}

}  // namespace
JAWMESH_COMMAND(100, addCompletionCommand);
}  // namespace jawmesh
