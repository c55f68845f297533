#include "cli/Commands.h"
#include "io/Error.h"

namespace jawmesh {
void addPhantomCommand(CLI::App& app, GlobalOptions& global) {
    auto* cmd = app.add_subcommand("phantom", "(under construction)");
    cmd->callback([] { throw Error("jawmesh phantom is not implemented yet"); });
}
}  // namespace jawmesh
