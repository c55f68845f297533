// jawmesh run: the main job, case folder -> validated labeled meshes for every jaw.
#include "batch/MemoryEstimate.h"
#include "cli/Commands.h"
#include "cli/NumberChecks.h"
#include "cli/Pipeline.h"
#include "io/Error.h"

#include <cstdio>
#include <memory>

namespace jawmesh {
namespace {

struct RunCommandOptions {
    std::string caseDir;
    std::string outDir;
    std::string jaw;
    std::string config;
    std::string fromVdb;
    std::string edits;
    double voxelMm = 0;
    bool writeLevelSets = false;
    bool memoryCheck = true;
};

void runCase(const RunCommandOptions& opt, const GlobalOptions& global) {
    RunOptions options = defaultRunOptions();
    if (!opt.config.empty()) applyRunConfig(opt.config, options);
    if (opt.voxelMm > 0) options.voxelSizeMm = opt.voxelMm;
    if (opt.writeLevelSets) options.writeLevelSets = true;
    if (!opt.fromVdb.empty()) options.fromVdb = opt.fromVdb;
    if (!opt.edits.empty()) options.edits = readEditFile(opt.edits);
    if (opt.memoryCheck) options.memoryLimitBytes = availableMemoryBytes();
    const CaseInfo info = discoverCase(opt.caseDir);
    int ran = 0;
    for (const JawCase& jawCase : info.jaws) {
        if (!opt.jaw.empty() && jawName(jawCase.jaw) != opt.jaw) continue;
        const nlohmann::json record =
            runJawStaged(jawCase, options, opt.outDir + "/" + jawName(jawCase.jaw), terminalProgress(global));
        ++ran;
        if (!global.quiet)
            std::fprintf(stderr, "%s: %zu nodes, %zu tets, %.1f s -> %s/%s\n", jawName(jawCase.jaw).c_str(),
                         record["mesh"]["nodes"].get<std::size_t>(), record["mesh"]["tets"].get<std::size_t>(),
                         record["seconds"].get<double>(), opt.outDir.c_str(), jawName(jawCase.jaw).c_str());
    }
    if (ran == 0) throw Error(opt.caseDir, "the case has no " + opt.jaw + " jaw");
}

void addRunCommand(CLI::App& app, GlobalOptions& global) {
    auto opt = std::make_shared<RunCommandOptions>();
    auto* cmd = app.add_subcommand(
        "run", "Case folder -> conformal labeled tetrahedral meshes of every jaw (bone, teeth, PDLs), validated, in "
               "<out>/<jaw>/{volumetric_meshes,surface_meshes} with run.json");
    cmd->add_option("case", opt->caseDir, "Case folder (Open-Full-Jaw layout: <case>/input/<jaw>/...)")->required();
    cmd->add_option("-o,--output", opt->outDir, "Output folder")->required();
    cmd->add_option("--jaw", opt->jaw, "Only this jaw")->check(CLI::IsMember({"mandible", "maxilla"}));
    cmd->add_option("--config", opt->config, "JSON file of options (keys as recorded in run.json)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--voxel", opt->voxelMm, "Level-set voxel size, mm (else the --config file's, else the default)")
        ->check(positiveNumber())
        ->default_str(CLI::detail::to_string(RunOptions{}.voxelSizeMm));
    cmd->add_flag("--write-levelsets", opt->writeLevelSets, "Also write the carved level sets (.vdb)");
    cmd->add_option("--from-vdb", opt->fromVdb, "Resume from a carved level-set folder (e.g. an edited one)")
        ->check(CLI::ExistingDirectory);
    cmd->add_option("--edits", opt->edits,
                    "JSON file of what-if edits (extract, bone_loss, pdl_thickness; examples/edit_levelsets) applied before carving")
        ->check(CLI::ExistingFile);
    cmd->add_flag("!--no-memory-check", opt->memoryCheck,
                  "Run even when the memory estimate exceeds the available memory");
    cmd->callback([opt, &global] { runCase(*opt, global); });
}

}  // namespace
JAWMESH_COMMAND(50, addRunCommand);
}  // namespace jawmesh
