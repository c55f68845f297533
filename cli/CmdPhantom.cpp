// PLACEHOLDER until the phantom stage lands; replaced by its real command.
#include "cli/Commands.h"
#include "io/Error.h"

namespace jawmesh {
namespace {
void addPhantomCommand(CLI::App& app, GlobalOptions&) {
    auto* cmd = app.add_subcommand("phantom", "(under construction)");
    cmd->callback([] { throw Error("jawmesh phantom is not implemented yet"); });
}
}  // namespace
JAWMESH_COMMAND(10, addPhantomCommand);
}  // namespace jawmesh
