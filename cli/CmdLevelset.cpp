// PLACEHOLDER until the levelset stage lands; replaced by its real command.
#include "cli/Commands.h"
#include "io/Error.h"

namespace jawmesh {
namespace {
void addLevelsetCommand(CLI::App& app, GlobalOptions&) {
    auto* cmd = app.add_subcommand("levelset", "(under construction)");
    cmd->callback([] { throw Error("jawmesh levelset is not implemented yet"); });
}
}  // namespace
JAWMESH_COMMAND(10, addLevelsetCommand);
}  // namespace jawmesh
