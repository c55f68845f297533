// jawmesh: dense CBCT segmentation surfaces -> conformal labeled FE meshes of jaws.
#include "cli/Commands.h"
#include "cli/NumberChecks.h"
#include "cli/TerminalProgress.h"
#include "io/Error.h"
#include "io/HugePageMalloc.h"

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

/// One line for a command-line error: CLI11's message (it names the option) and where help is.
std::string usageErrorLine(const CLI::App& app, const CLI::ParseError& error) {
    // An argument nobody takes is the user's mistake even when CLI11 first finds a missing one.
    const std::vector<std::string> extra = app.remaining(true);
    std::string message = extra.empty() ? error.what() : "unknown argument " + extra.front();
    std::replace(message.begin(), message.end(), '\n', ' ');
    std::string command = "jawmesh";
    for (const CLI::App* sub = &app; sub && !sub->get_subcommands().empty();) {
        sub = sub->get_subcommands().back();
        command += " " + sub->get_name();
    }
    return message + " (see `" + command + " --help`)";
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
    // Global options may also follow the subcommand (`jawmesh run case -o out --quiet`); every
    // option's help shows its default, taken from the variable it is bound to.
    app.fallthrough();
    app.option_defaults()->always_capture_default();
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
        ->check(nonNegativeNumber());
    addRegisteredCommands(app, global);

    app.preparse_callback([](std::size_t) { openvdb::initialize(); });
    // Arguments parsed and checked, no command run yet: huge pages for malloc where the kernel
    // waits to be asked (io/HugePageMalloc.h). A second start costs about 70 ms (the dynamic
    // linking again), so usage errors, --help and the completion script go without.
    app.parse_complete_callback([&app, argv] {
        const std::vector<CLI::App*> used = app.get_subcommands();
        if (!used.empty() && used.front()->get_name() != "completion") reexecWithHugePageMalloc(argv);
    });
    try {
        TerminalProgress::installInterruptHandler();
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::fprintf(stderr, "jawmesh: usage error: %s\n", usageErrorLine(app, e).c_str());
        return kExitUsage;
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
