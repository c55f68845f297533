// jawmesh surface: carved label field -> simplified interface complex for TetGen (.poly with facet
// markers = label pairs and one seed per region component), one .ply per region, summary JSON.
#include "cli/Commands.h"
#include "cli/NumberChecks.h"
#include "cli/RunOptions.h"
#include "filters/ExtractInterfaces.h"
#include "filters/SimplifyInterfaces.h"
#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/PolyWriter.h"
#include "io/ResourceUsage.h"
#include "io/StagedFolder.h"
#include "levelset/LabelFieldIO.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

namespace jawmesh {
namespace {

/// Defaults are `jawmesh run`'s (defaultRunOptions): the same carve gives the same surface.
struct SurfaceCliOptions {
    std::string carveDir;
    std::string output;
    SimplifyOptions simplify = defaultRunOptions().simplify;
    ExtractOptions extract = defaultRunOptions().extract;
    bool simplifyOn = true;
    bool json = false;
};

void runSurface(const SurfaceCliOptions& opt, const GlobalOptions& global) {
    const auto start = std::chrono::steady_clock::now();
    Progress& progress = terminalProgress(global);
    // Accept the jaw folder of `jawmesh carve` / `run --write-levelsets` or its levelsets/ folder.
    std::string dir = opt.carveDir;
    if (std::filesystem::exists(dir + "/levelsets/labels.vdb")) dir += "/levelsets";
    LabelField field = readLabelField(dir);
    const double voxelMm = field.voxelSizeMm;
    const Jaw jawOfField = field.jaw;
    const double secondsRead = secondsSince(start);

    const auto tExtract = std::chrono::steady_clock::now();
    const double cpuStart = processCpuSeconds();
    ExtractOptions extract = opt.extract;
    extract.findSeeds = !opt.simplifyOn;  // simplification places them on its output
    extract.adaptive = matchedTo(opt.simplify, extract.adaptive);
    ExtractStats extractStats;
    InterfaceComplex complex = extractInterfaces(std::move(field), extract, progress, &extractStats);
    const double secondsExtract = secondsSince(tExtract);
    const double cpuExtract = processCpuSeconds() - cpuStart;
    SimplifyStats stats;
    if (opt.simplifyOn) complex = simplifyInterfaces(complex, opt.simplify, progress, &stats);
    else complex = withoutCarried(std::move(complex));
    const double cpuSimplify = processCpuSeconds() - cpuStart - cpuExtract;

    const std::string jaw = jawName(jawOfField);
    StagedFolder staged(opt.output);
    writeTetgenPoly(complex, staged.path() + "/" + jaw + ".poly");
    writeRegionBoundaries(complex, staged.path() + "/regions", "ply");
    nlohmann::json j = {{"input", opt.carveDir},
                        {"jaw", jaw},
                        {"voxel_mm", voxelMm},
                        {"triangles", complex.surface.triangles.size()},
                        {"vertices", complex.surface.vertices.size()},
                        {"seeds", complex.seeds.size()},
                        {"seconds", {{"read", secondsRead}, {"extract", secondsExtract}, {"simplify", stats.seconds},
                                     {"total", secondsSince(start)}}},
                        {"cpu_seconds", {{"extract", cpuExtract}, {"simplify", cpuSimplify}}},
                        {"peak_memory_bytes", peakResidentMemoryBytes()}};
    j["adaptive"] = toJson(extractStats.adaptive);
    if (opt.simplifyOn) {
        j["simplify"] = toJson(stats);
        j["simplify"]["options"] = toJson(opt.simplify);
    }
    writeFileAtomically(staged.path() + "/surface.json", [&](std::ostream& os) { os << j.dump(2) << "\n"; }, false);
    staged.commit(StagedFolder::Mode::Merge);  // the folder is the user's: other files in it stay
    if (opt.json) std::cout << j.dump() << std::endl;
}

void addSurfaceCommand(CLI::App& app, GlobalOptions& global) {
    auto opt = std::make_shared<SurfaceCliOptions>();
    auto* cmd = app.add_subcommand(
        "surface",
        "Carved label field -> conformal interface surface, simplified with an error bound. Writes "
        "<out>/<jaw>.poly (TetGen: facet marker = label pair, one region seed per component), "
        "<out>/regions/<label>.ply and <out>/surface.json (triangles per interface, error, angles, seconds).");
    cmd->add_option("carve-dir", opt->carveDir, "Jaw folder written by `jawmesh carve` (or its levelsets/ folder)")
        ->required()
        ->check(CLI::ExistingDirectory);
    cmd->add_option("-o,--output", opt->output, "Output folder")->required();
    cmd->add_option("--tooth-error", opt->simplify.toothErrorMm,
                    "Error bound on the crowns (tooth / outside) and the crest cap, mm")
        ->check(nonNegativeNumber());
    cmd->add_option("--pdl-error", opt->simplify.pdlErrorMm, "Error bound on tooth / PDL and PDL / bone, mm")
        ->check(nonNegativeNumber());
    cmd->add_option("--pdl-max-edge", opt->simplify.pdlMaxEdgeMm,
                    "Longest edge on tooth / PDL and PDL / bone, mm")
        ->check(positiveNumber());
    cmd->add_option("--cap-max-edge", opt->simplify.capMaxEdgeMm,
                    "Longest edge on the crest cap (PDL / outside), mm")
        ->check(positiveNumber());
    cmd->add_option("--bone-error", opt->simplify.boneErrorMm, "Error bound on the bone surface near teeth, mm")
        ->check(nonNegativeNumber());
    cmd->add_option("--bone-far-error", opt->simplify.boneFarErrorMm,
                    "Error bound on the bone surface farther than --near-teeth from any tooth, mm")
        ->check(nonNegativeNumber());
    cmd->add_option("--near-teeth", opt->simplify.boneNearTeethMm, "Bone within this distance of a tooth or PDL is near, mm")
        ->check(nonNegativeNumber());
    cmd->add_option("--min-angle", opt->simplify.minAngleDeg, "Smallest angle a collapse may create, degrees")
        ->check(CLI::Range(0.0, 59.0));
    cmd->add_option("--min-wedge", opt->simplify.minWedgeDeg,
                    "Smallest angle a region may come to span around an edge, degrees (0 = off)")
        ->check(CLI::Range(0.0, 89.0));
    cmd->add_flag("!--no-simplify", opt->simplifyOn, "Write the raw extraction");
    cmd->add_flag("--json", opt->json, "Also print the summary as one JSON object on stdout");
    cmd->callback([opt, &global] { runSurface(*opt, global); });
}

}  // namespace
JAWMESH_COMMAND(40, addSurfaceCommand);
}  // namespace jawmesh
