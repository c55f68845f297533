#include "cli/Commands.h"
#include "io/Error.h"

namespace jawmesh {
void addLevelsetCommand(CLI::App& app, GlobalOptions& global) {
    auto* cmd = app.add_subcommand("levelset", "(under construction)");
    cmd->callback([] { throw Error("jawmesh levelset is not implemented yet"); });
}
}  // namespace jawmesh
