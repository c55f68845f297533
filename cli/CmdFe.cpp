// jawmesh fe <out>/<jaw>: FE decks of a meshed jaw (tipping or biting) in FEBio, PolyFEM and
// CalculiX formats, optionally solved with CalculiX (ccx) and summarised.
#include "cli/Commands.h"
#include "cli/NumberChecks.h"
#include "fe/FeDecks.h"
#include "fe/JoinMeshes.h"
#include "fe/RunCalculix.h"
#include "fe/Scenario.h"
#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/GmshReader.h"
#include "io/StagedFolder.h"
#include "io/ToothAxes.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

namespace fs = std::filesystem;

namespace jawmesh {
namespace {

/// `jawmesh fe --help`: what the command does and writes.
constexpr const char* kFeDescription =
    "FE decks of a meshed jaw into <out>/<jaw>/simulation/: <scenario>.feb (FEBio 4), <scenario>_polyfem.json "
    "(+ .msh and selections), <scenario>.inp (CalculiX/Abaqus). Tipping: bone base fixed, 1 N lingual per tooth "
    "over a labial crown patch; biting (both jaws: the other jaw's mesh is taken from the sibling folder "
    "<out>/<other jaw>): maxilla top fixed, 200 N up on the mandible base, contact between the crowns. --solve "
    "runs ccx and writes <scenario>_calculix_summary.json.";


struct FeCliOptions {
    std::string jawDir;
    std::string scenario = "tipping";
    std::vector<std::string> formats{"feb", "polyfem", "inp"};
    int order = 1;
    bool solve = false;
    std::string axesPath;
    std::string materialsPath;
    int threads = 1;
};

void runFe(const FeCliOptions& opt, const GlobalOptions& global) {
    const fs::path jawDir = fs::path(opt.jawDir).lexically_normal();
    const std::string jaw = (jawDir.filename().empty() ? jawDir.parent_path() : jawDir).filename().string();
    const std::string meshPath = (jawDir / "volumetric_meshes" / (jaw + ".msh")).string();
    if (!fs::exists(meshPath)) throw Error(meshPath, "no volume mesh here (run `jawmesh run` first; expected <out>/<jaw>/volumetric_meshes/<jaw>.msh)");
    TetMesh mesh = readGmsh(meshPath);
    if (opt.scenario == "biting" && (jaw == "mandible" || jaw == "maxilla")) {
        // Each jaw is meshed in its own folder: biting takes the other jaw from the sibling folder.
        const std::string other = jaw == "mandible" ? "maxilla" : "mandible";
        const fs::path otherPath = (jawDir.filename().empty() ? jawDir.parent_path() : jawDir).parent_path() / other /
                                   "volumetric_meshes" / (other + ".msh");
        const bool hasOther = std::find(mesh.labels.begin(), mesh.labels.end(), boneLabel(jaw == "mandible" ? Jaw::Maxilla : Jaw::Mandible)) !=
                              mesh.labels.end();
        if (!hasOther) {
            if (!fs::exists(otherPath))
                throw Error(otherPath.string(), "the biting scenario needs both jaws: mesh the " + other + " too (`jawmesh run` writes it here)");
            mesh = joinMeshes(mesh, readGmsh(otherPath.string()));
        }
    }

    FeDeckOptions o;
    o.formats = {opt.formats.begin(), opt.formats.end()};
    o.order = opt.order;
    if (!opt.materialsPath.empty()) {
        std::ifstream in(opt.materialsPath);
        if (!in) throw Error(opt.materialsPath, "cannot open materials file");
        nlohmann::json j;
        try {
            j = nlohmann::json::parse(in);
        } catch (const nlohmann::json::exception& e) {
            throw Error(opt.materialsPath, std::string("invalid JSON: ") + e.what());
        }
        applyMaterialOverrides(j, o.materials, opt.materialsPath);
    }

    std::vector<std::string> written;
    FeScenario scenario;
    std::vector<std::string> notes;
    // The decks of a scenario go together: staged, then moved into <jaw>/simulation/ at once.
    StagedFolder staged(jawDir.string());
    const fs::path stagedDir = staged.path();
    if (opt.scenario == "tipping") {
        const std::map<int, ToothAxes> given = opt.axesPath.empty() ? std::map<int, ToothAxes>() : readToothAxes(opt.axesPath);
        const auto axes = axesForMesh(mesh, given, &notes);
        scenario = tippingScenario(mesh, axes, o.tipping);
        writeToothAxes(axes, (stagedDir / "simulation" / "tipping_axes.json").string());
    } else {
        scenario = bitingScenario(mesh, o.biting);
    }
    scenario.notes.insert(scenario.notes.begin(), notes.begin(), notes.end());
    written = writeScenarioDecks(mesh, scenario, stagedDir.string(), o);
    staged.commit(StagedFolder::Mode::Merge);  // the jaw folder's other files (the mesh) stay
    if (!global.quiet) {
        for (const std::string& p : written) std::cerr << "wrote " << (jawDir / fs::path(p).lexically_relative(stagedDir)).string() << "\n";
        for (const std::string& n : scenario.notes) std::cerr << "note: " << n << "\n";
    }
    if (!opt.solve) return;

    const std::string inp = (jawDir / "simulation" / (scenario.name + ".inp")).string();
    if (!o.formats.count("inp") || !fs::exists(inp))
        throw Error(inp, "--solve runs CalculiX on the .inp deck: add inp to --format");
    if (!global.quiet) std::cerr << "solving " << inp << " with CalculiX...\n";
    const CalculixRun run = runCalculix(inp, opt.threads);
    nlohmann::json summary = calculixSummary(scenario, run, inp, &mesh);
    summary["deck"] = inp;
    summary["order"] = opt.order;
    const std::string summaryPath = (jawDir / "simulation" / (scenario.name + "_calculix_summary.json")).string();
    writeFileAtomically(summaryPath, [&](std::ostream& out) { out << summary.dump(2) << "\n"; }, false);
    std::cout << summary.dump(2) << std::endl;
    if (run.status != "completed") throw Error(inp, "CalculiX " + run.status + ": " + run.message);
}

void addFeCommand(CLI::App& app, GlobalOptions& global) {
    auto opt = std::make_shared<FeCliOptions>();
    auto* cmd = app.add_subcommand("fe", kFeDescription);
    cmd->add_option("jaw_dir", opt->jawDir, "A jaw folder of a run: <out>/<jaw>")->required()->check(CLI::ExistingDirectory);
    cmd->add_option("--scenario", opt->scenario, "tipping | biting")->check(CLI::IsMember({"tipping", "biting"}))->capture_default_str();
    cmd->add_option("--format", opt->formats, "Comma-separated: feb,polyfem,inp")
        ->delimiter(',')
        ->check(CLI::IsMember({"feb", "polyfem", "inp"}))
        ->capture_default_str();
    cmd->add_option("--order", opt->order, "Element order of .feb and .inp: 1 (tet4/C3D4) or 2 (tet10/C3D10)")
        ->check(CLI::IsMember({1, 2}))
        ->capture_default_str();
    cmd->add_option("--axes", opt->axesPath, "Tooth axes JSON (teeth_axes_<jaw>.json); default: computed from the mesh")
        ->check(CLI::ExistingFile);
    cmd->add_option("--materials", opt->materialsPath, "JSON overriding materials: {\"pdl\": {\"E\": 68.9, \"nu\": 0.45, \"rho\": 1.142e-9}}")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--solve", opt->solve, "Run CalculiX (ccx) on the .inp deck and summarise its results");
    cmd->add_option("--solver-threads", opt->threads, "Threads for ccx (OMP_NUM_THREADS)")->check(positiveNumber())->capture_default_str();
    cmd->callback([opt, &global] { runFe(*opt, global); });
}

}  // namespace
JAWMESH_COMMAND(70, addFeCommand);
}  // namespace jawmesh
