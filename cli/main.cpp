// jawmesh: dense CBCT segmentation surfaces -> conformal labeled FE meshes of jaws.
#include "cli/Commands.h"
#include "cli/TerminalProgress.h"
#include "io/Error.h"

#include <openvdb/openvdb.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#ifndef JAWMESH_VERSION
#define JAWMESH_VERSION "unknown"
#endif

namespace jawmesh {
namespace {
std::vector<std::pair<int, CommandAdder>>& registry() {
    static std::vector<std::pair<int, CommandAdder>> commands;
    return commands;
}
}  // namespace

CommandRegistration::CommandRegistration(int order, CommandAdder add) { registry().emplace_back(order, add); }

void addRegisteredCommands(CLI::App& app, GlobalOptions& global) {
    auto commands = registry();
    std::stable_sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& entry : commands) entry.second(app, global);
}

Progress& terminalProgress(const GlobalOptions& global) {
    static TerminalProgress loud(false);
    static TerminalProgress quiet(true);
    return global.quiet ? static_cast<Progress&>(quiet) : static_cast<Progress&>(loud);
}

}  // namespace jawmesh

int main(int argc, char** argv) {
    using namespace jawmesh;
    CLI::App app{"jawmesh: dense jaw segmentation surfaces -> conformal labeled tetrahedral FE models"};
    app.set_version_flag("--version", std::string("jawmesh ") + JAWMESH_VERSION);
    app.require_subcommand(1);
    GlobalOptions global;
    app.add_flag("-q,--quiet", global.quiet, "No progress output");
    // Results never depend on the thread count; this only bounds the cores used.
    std::unique_ptr<tbb::global_control> threadLimit;
    app.add_option_function<int>(
           "--threads",
           [&](int n) {
               global.threads = n;
               if (n > 0)
                   threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                       static_cast<std::size_t>(n));
           },
           "Worker threads (0 = all cores)")
        ->check(CLI::NonNegativeNumber);
    addRegisteredCommands(app, global);

    app.preparse_callback([](std::size_t) { openvdb::initialize(); });
    try {
        TerminalProgress::installInterruptHandler();
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const Cancelled& e) {
        std::fprintf(stderr, "\njawmesh: %s; no partial output written\n", e.what());
        return kExitCancelled;
    } catch (const Error& e) {
        std::fprintf(stderr, "jawmesh: error: %s\n", e.what());
        return kExitFailure;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "jawmesh: error: out of memory (try a larger --voxel)\n");
        return kExitFailure;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "jawmesh: internal error: %s\n", e.what());
        return kExitFailure;
    }
    return 0;
}
