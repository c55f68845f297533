// jawmesh eval <mesh> [--input <case>/input/<jaw>] -o <dir>: the accuracy and quality report of a
// labeled tet mesh (report.json, report.html, sections/*.png).
#include "cli/Commands.h"
#include "cli/NumberChecks.h"
#include "cli/EvalReport.h"
#include "io/Error.h"
#include "io/GmshReader.h"
#include "io/MeshIO.h"
#include "io/StagedFolder.h"

#include <cstdio>
#include <iostream>
#include <memory>

namespace jawmesh {
namespace {

/// `jawmesh eval --help`: what the command does and writes.
constexpr const char* kEvalDescription =
    "Accuracy and quality report of a labeled tet mesh: conformity, element quality per region (radius ratio, "
    "volume-edge ratio, radius-edge ratio, dihedral angles) with histograms, two-sided Hausdorff and mean distances "
    "to the input surfaces (crown and root apart), PDL thickness per tooth, cross-section pictures -> "
    "<dir>/report.json, report.html, sections/*.png";


struct EvalCliOptions {
    std::string meshPath;
    std::string inputPath;
    std::string outDir;
    std::string jaw;
    EvalOptions eval;
    bool json = false;
};

/// The jaw of a mesh: its bone label, else the jaw of its teeth.
Jaw jawOfMesh(const TetMesh& mesh, const std::string& path) {
    for (Label l : mesh.labels)
        if (l == kMandibleBoneLabel || l == kMaxillaBoneLabel) return l == kMandibleBoneLabel ? Jaw::Mandible : Jaw::Maxilla;
    for (Label l : mesh.labels)
        if (isToothLike(labelKind(l))) return jawOfTooth(labelUnn(l));
    throw Error(path, "cannot tell the jaw of this mesh (no bone or tooth label); pass --jaw");
}

void runEval(const EvalCliOptions& opt, const GlobalOptions& global) {
    if (surfaceExtension(opt.meshPath) != "msh")
        throw Error(opt.meshPath, "eval reads Gmsh 4.1 .msh volume meshes (as `jawmesh run` writes them)");
    Progress& progress = terminalProgress(global);
    TetMesh mesh;
    {
        ProgressStage stage(progress, "eval: read mesh");
        mesh = readGmsh(opt.meshPath);
    }
    if (mesh.tets.empty()) throw Error(opt.meshPath, "the mesh has no tetrahedra");
    JawSurfaces input;
    const bool haveInput = !opt.inputPath.empty();
    if (haveInput) {
        const Jaw jaw = opt.jaw.empty() ? jawOfMesh(mesh, opt.meshPath) : jawFromName(opt.jaw);
        ProgressStage stage(progress, "eval: read input");
        input = loadEvalInput(opt.inputPath, jaw, {}, progress);
    }
    StagedFolder staged(opt.outDir);
    const nlohmann::json report =
        writeEvalReport(mesh, haveInput ? &input : nullptr, opt.eval, staged.path(), opt.meshPath, progress);
    staged.commit(StagedFolder::Mode::Merge);  // the folder is the user's: other files in it stay
    if (opt.json) std::cout << report.dump(2) << std::endl;
    if (!global.quiet) {
        std::fprintf(stderr, "%s\nwrote %s/report.html, report.json (%.1f s)\n", report["verdict"]["line"].get<std::string>().c_str(),
                     opt.outDir.c_str(), report.value("seconds", 0.0));
    }
}

void addEvalCommand(CLI::App& app, GlobalOptions& global) {
    auto opt = std::make_shared<EvalCliOptions>();
    auto* cmd = app.add_subcommand("eval", kEvalDescription);
    cmd->add_option("mesh", opt->meshPath, "Volume mesh (.msh), e.g. <out>/<jaw>/volumetric_meshes/<jaw>.msh")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--input", opt->inputPath, "Input surfaces: <case>/input/<jaw> (or the case folder)")->check(CLI::ExistingDirectory);
    cmd->add_option("-o,--output", opt->outDir, "Report folder")->required();
    cmd->add_option("--jaw", opt->jaw, "Jaw of the input when --input is a case folder (default: from the mesh labels)")
        ->check(CLI::IsMember({"mandible", "maxilla"}));
    cmd->add_option("--spacing", opt->eval.sampleSpacingMm, "Area-sample spacing for means and percentiles, mm")
        ->check(positiveNumber())
        ->capture_default_str();
    cmd->add_option("--tolerance", opt->eval.hausdorffToleranceMm, "Maxima (Hausdorff) exact to this, mm")
        ->check(positiveNumber())
        ->capture_default_str();
    cmd->add_option("--pdl-target", opt->eval.pdlTargetMm, "PDL target thickness for the verdict, mm (0: measured only, e.g. a PDL kept from a label map)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    cmd->add_option("--pdl-tolerance", opt->eval.pdlToleranceMm, "Allowed PDL deviation (p05 and p95), mm")
        ->check(nonNegativeNumber())
        ->capture_default_str();
    cmd->add_option("--crown-tolerance", opt->eval.crownToleranceMm, "Allowed crown Hausdorff distance, mm")
        ->check(positiveNumber())
        ->capture_default_str();
    cmd->add_option("--cervical-band", opt->eval.cervicalBandMm,
                    "Crown faces this near the root form the cervical band, measured apart from the crown, mm")
        ->check(nonNegativeNumber())
        ->capture_default_str();
    cmd->add_option("--min-dihedral", opt->eval.minDihedralDeg, "Quality check: smallest acceptable dihedral angle, degrees")
        ->capture_default_str();
    cmd->add_flag("--json", opt->json, "Also print report.json to stdout");
    cmd->callback([opt, &global] { runEval(*opt, global); });
}

}  // namespace
JAWMESH_COMMAND(55, addEvalCommand);
}  // namespace jawmesh
