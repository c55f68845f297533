// jawmesh: dense CBCT segmentation surfaces -> conformal labeled FE meshes of jaws.
#include "cli/Commands.h"
#include "cli/TerminalProgress.h"
#include "io/Error.h"

#include <openvdb/openvdb.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <memory>

#ifndef JAWMESH_VERSION
#define JAWMESH_VERSION "unknown"
#endif

int main(int argc, char** argv) {
    using namespace jawmesh;
    CLI::App app{"jawmesh: dense jaw segmentation surfaces -> conformal labeled tetrahedral FE models"};
    app.set_version_flag("--version", std::string("jawmesh ") + JAWMESH_VERSION);
    app.require_subcommand(1);
    GlobalOptions global;
    app.add_flag("-q,--quiet", global.quiet, "No progress output")->configurable();
    app.add_option("--threads", global.threads, "Worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
    addPhantomCommand(app, global);
    addLevelsetCommand(app, global);

    std::unique_ptr<tbb::global_control> threadLimit;
    app.parse_complete_callback([&] {
        if (global.threads > 0)
            threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                static_cast<std::size_t>(global.threads));
    });
    try {
        openvdb::initialize();
        TerminalProgress::installInterruptHandler();
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const Cancelled& e) {
        std::fprintf(stderr, "jawmesh: %s; no output written\n", e.what());
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
