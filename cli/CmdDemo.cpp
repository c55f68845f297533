// jawmesh demo: the built-in synthetic phantom through the whole pipeline (the README's first command).
#include "batch/MemoryEstimate.h"
#include "cli/Commands.h"
#include "cli/Pipeline.h"
#include "levelset/Phantom.h"

#include <cstdio>
#include <memory>

namespace jawmesh {
namespace {

struct DemoOptions {
    std::string outDir = "out/demo";
    int teeth = 2;  // a whole run in minutes on 2 cores; --teeth 14 for a full arch
};

void runDemo(const DemoOptions& opt, const GlobalOptions& global) {
    Progress& progress = terminalProgress(global);
    const std::string caseDir = opt.outDir + "/case";
    PhantomOptions phantom;
    phantom.teeth = opt.teeth;
    {
        ProgressStage stage(progress, "phantom");
        writePhantomCase({makePhantom(phantom, progress)}, caseDir);
    }
    const CaseInfo info = discoverCase(caseDir);
    RunOptions options = defaultRunOptions();
    options.memoryLimitBytes = availableMemoryBytes();
    for (const JawCase& jawCase : info.jaws)
        runJawStaged(jawCase, options, opt.outDir + "/" + jawName(jawCase.jaw), progress);
    if (!global.quiet) std::fprintf(stderr, "demo: case in %s, meshes in %s/<jaw>/\n", caseDir.c_str(), opt.outDir.c_str());
}

void addDemoCommand(CLI::App& app, GlobalOptions& global) {
    auto opt = std::make_shared<DemoOptions>();
    auto* cmd = app.add_subcommand("demo", "Generate the synthetic jaw phantom and run the whole pipeline on it");
    cmd->add_option("-o,--output", opt->outDir, "Output folder");
    cmd->add_option("--teeth", opt->teeth, "Teeth in the phantom")->check(CLI::Range(1, 16));
    cmd->callback([opt, &global] { runDemo(*opt, global); });
}

}  // namespace
JAWMESH_COMMAND(60, addDemoCommand);
}  // namespace jawmesh
