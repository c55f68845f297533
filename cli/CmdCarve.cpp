// jawmesh carve: case -> level sets -> carved PDLs -> label field (.vdb) + summary.json.
#include "batch/MemoryEstimate.h"
#include "cli/Commands.h"
#include "cli/NumberChecks.h"
#include "cli/Pipeline.h"
#include "cli/RunOptions.h"
#include "io/AtomicFile.h"
#include "io/Case.h"
#include "io/Error.h"
#include "io/ResourceUsage.h"
#include "io/StagedFolder.h"
#include "levelset/CarveGaps.h"
#include "levelset/JawInput.h"
#include "levelset/JawLevelSets.h"
#include "levelset/JawLevelSetsIO.h"
#include "levelset/LabelFieldIO.h"
#include "levelset/MeshToLevelSet.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

namespace jawmesh {
namespace {

/// Defaults are `jawmesh run`'s (defaultRunOptions): the same case gives the same carve.
struct CarveCliOptions {
    std::string caseDir;
    std::string output;
    std::string jaw = "mandible";
    double voxelMm = defaultRunOptions().voxelSizeMm;
    double bandVoxels = defaultRunOptions().bandVoxels;
    CarveOptions carve = defaultRunOptions().carve;  ///< bound to flags; profile and axes are filled in runCarve
    std::vector<double> profile;
    bool json = false;
    bool memoryCheck = true;
};

void runCarve(const CarveCliOptions& opt, const GlobalOptions& global) {
    const auto start = std::chrono::steady_clock::now();
    Progress& progress = terminalProgress(global);
    const Jaw jaw = jawFromName(opt.jaw);
    const CaseInfo info = discoverCase(opt.caseDir);
    const JawCase* jc = nullptr;
    for (const auto& j : info.jaws)
        if (j.jaw == jaw) jc = &j;
    if (!jc) throw Error(opt.caseDir, "case has no " + opt.jaw);
    const JawSurfaces surfaces = loadJawInput(*jc, LoadOptions(), progress);
    requireMemoryFits(surfaces, opt.voxelMm, opt.memoryCheck ? availableMemoryBytes() : 0,
                      jc->folder);
    const double secondsLoad = secondsSince(start);
    const auto peakLoad = peakResidentMemoryBytes();

    CarveOptions co = opt.carve;
    co.axes = surfaces.axes;
    if (!opt.profile.empty()) {
        if (opt.profile.size() != 3) throw Error("--pdl-profile takes three values: cervical,mid,apical (mm)");
        co.profile = PdlProfile{opt.profile[0], opt.profile[1], opt.profile[2]};
    }
    co = carveOptionsFor(surfaces, co, opt.voxelMm);

    const auto tLevel = std::chrono::steady_clock::now();
    const JawLevelSets levelSets = jawLevelSets(surfaces, *jc, opt.voxelMm, opt.bandVoxels, defaultRunOptions().boneFarBandVoxels,
                                                toothBandVoxels(co, opt.voxelMm), progress);
    const double secondsLevelSets = secondsSince(tLevel);
    const auto peakLevelSets = peakResidentMemoryBytes();

    CarveSummary summary;
    const LabelField field = carveJaw(jaw, *levelSets.bone, levelSets.teeth, co, summary, progress);

    StagedFolder staged(opt.output + "/" + jawName(jaw));
    const std::string jawDir = staged.path();
    writeEditableFolder(field, levelSets, jaw, co, nlohmann::json::array(), jawDir + "/levelsets");  // `jawmesh edit` carves it again
    nlohmann::json j = toJson(summary);
    j["options"] = toJson(co);
    j["case"] = opt.caseDir;
    j["jaw"] = jawName(jaw);
    j["notes"] = surfaces.notes;
    j["seconds"] = {{"load", secondsLoad}, {"level_sets", secondsLevelSets}, {"carve", summary.seconds}, {"total", secondsSince(start)}};
    j["peak_memory_bytes"] = peakResidentMemoryBytes();
    // Per stage: wall seconds and the process peak resident memory at its end (monotonic).
    nlohmann::json stages = nlohmann::json::array();
    stages.push_back({{"name", "load"}, {"seconds", secondsLoad}, {"peak_memory_bytes", peakLoad}});
    stages.push_back({{"name", "level sets"}, {"seconds", secondsLevelSets}, {"peak_memory_bytes", peakLevelSets}});
    for (const auto& st : summary.stages)
        stages.push_back({{"name", "carve: " + st.name}, {"seconds", st.seconds}, {"peak_memory_bytes", st.peakMemoryBytes}});
    j["stages"] = stages;
    writeFileAtomically(jawDir + "/summary.json", [&](std::ostream& os) { os << j.dump(2) << "\n"; }, false);
    staged.commit(StagedFolder::Mode::Replace);
    if (opt.json) std::cout << j.dump() << std::endl;
    if (!global.quiet)
        for (const auto& w : summary.warnings) std::cerr << "warning: " << w << "\n";
}

void addCarveCommand(CLI::App& app, GlobalOptions& global) {
    auto opt = std::make_shared<CarveCliOptions>();
    auto* cmd = app.add_subcommand(
        "carve",
        "Case -> labelled grids: roots eroded, PDL of the requested thickness between root and socket with a smooth "
        "cap at the alveolar crest, crowns kept, teeth kept apart. Writes <out>/<jaw>/levelsets/{labels,bone_*,"
        "tooth_*,pdl_*}.vdb and <out>/<jaw>/summary.json (PDL volume and thickness statistics per tooth, warnings).");
    cmd->add_option("case", opt->caseDir, "Case folder (Open-Full-Jaw layout)")->required()->check(CLI::ExistingDirectory);
    cmd->add_option("-o,--output", opt->output, "Output folder")->required();
    cmd->add_option("--jaw", opt->jaw, "mandible | maxilla")->check(CLI::IsMember({"mandible", "maxilla"}));
    cmd->add_option("--voxel", opt->voxelMm, "Voxel size, mm")->check(positiveNumber());
    cmd->add_option("--pdl-thickness", opt->carve.pdlThicknessMm, "PDL thickness, mm")->check(positiveNumber());
    cmd->add_option("--pdl-ratio", opt->carve.pdlRatio, "Share of the thickness taken from the root, 0..1")
        ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--pdl-profile", opt->profile, "Thickness along the root: cervical,mid,apical, mm (default: uniform)")
        ->delimiter(',')
        ->default_str("");
    cmd->add_option("--clearance", opt->carve.clearanceVoxels, "Gap between different teeth and PDLs, voxels")
        ->check(nonNegativeNumber());
    cmd->add_option("--gap-bridge", opt->carve.gapBridgeMm, "Widest root-socket gap bridged, mm")->check(nonNegativeNumber());
    cmd->add_option("--bone-shift", opt->carve.boneShiftMaxMm,
                    "Farthest a bridged gap moves the bone surface, mm (wider gaps erode the root less)")
        ->check(nonNegativeNumber());
    cmd->add_option("--apex-taper", opt->carve.apexTaperMm, "Root erosion falls to half over this length to the apex, mm (0 = off)")
        ->check(nonNegativeNumber());
    cmd->add_flag("--json", opt->json, "Also print the summary as one JSON object on stdout");
    cmd->add_flag("!--no-memory-check", opt->memoryCheck,
                  "Run even when the memory estimate exceeds the available memory");
    cmd->callback([opt, &global] { runCarve(*opt, global); });
}

}  // namespace
JAWMESH_COMMAND(30, addCarveCommand);
}  // namespace jawmesh
