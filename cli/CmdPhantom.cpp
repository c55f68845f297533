// jawmesh phantom <dir>: writes the synthetic jaw phantom as a case folder (see levelset/Phantom.h).
#include "cli/Commands.h"
#include "io/Error.h"
#include "io/Labels.h"
#include "levelset/Phantom.h"
#include "io/LabelCase.h"
#include "levelset/PhantomLabelVolume.h"

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace jawmesh {
namespace {

struct PhantomArgs {
    std::string dir;
    int teeth = 14;
    std::uint32_t seed = 1;
    std::string jaw = "mandible";
    double trianglesScale = 1.0;
    std::string labelMap;      ///< file name of a label volume to write instead of surfaces
    double voxelMm = 0.1;      ///< its voxel size
    double pdlLabelsMm = 0;    ///< > 0: PDL labels of this thickness
};

/// The phantom as a label volume per jaw (issue #23), instead of surfaces.
void writeLabelMaps(const PhantomArgs& args, const std::vector<Jaw>& jaws, const GlobalOptions& global) {
    for (Jaw jaw : jaws) {
        PhantomOptions options;
        options.jaw = jaw;
        options.teeth = args.teeth;
        options.seed = args.seed;
        std::map<int, ToothAxes> axes;
        const LabelVolume volume = phantomLabelVolume(options, {args.voxelMm, args.pdlLabelsMm}, &axes);
        writeLabelCase(volume, jaw, axes, args.dir, args.labelMap);
        if (!global.quiet)
            std::printf("%s: %d x %d x %d voxels of %.3f mm, %zu labels -> %s/input/%s/%s\n", jawName(jaw).c_str(), volume.size[0],
                        volume.size[1], volume.size[2], args.voxelMm, volume.segments.size(), args.dir.c_str(),
                        jawName(jaw).c_str(), args.labelMap.c_str());
    }
}

void runPhantom(const PhantomArgs& args, const GlobalOptions& global) {
    std::vector<Jaw> jaws;
    if (args.jaw == "both") jaws = {Jaw::Mandible, Jaw::Maxilla};
    else jaws = {jawFromName(args.jaw)};
    if (!args.labelMap.empty()) return writeLabelMaps(args, jaws, global);
    Progress& progress = terminalProgress(global);
    std::vector<PhantomJaw> made;
    for (Jaw jaw : jaws) {
        PhantomOptions options;
        options.jaw = jaw;
        options.teeth = args.teeth;
        options.seed = args.seed;
        options.trianglesScale = args.trianglesScale;
        made.push_back(makePhantom(options, progress));
    }
    writePhantomCase(made, args.dir);
    if (global.quiet) return;
    for (const PhantomJaw& jaw : made) {
        std::size_t teethTriangles = 0;
        for (const auto& [unn, mesh] : jaw.teeth) teethTriangles += mesh.triangles.size();
        std::printf("%s: bone %zu triangles, %zu teeth (%zu triangles), voxel %.3f mm -> %s/input/%s\n",
                    jawName(jaw.jaw).c_str(), jaw.bone.triangles.size(), jaw.teeth.size(), teethTriangles,
                    jaw.voxelSizeMm, args.dir.c_str(), jawName(jaw.jaw).c_str());
    }
}

void addPhantomCommand(CLI::App& app, GlobalOptions& global) {
    auto args = std::make_shared<PhantomArgs>();
    auto* cmd = app.add_subcommand("phantom", "Write a synthetic jaw case (bone, teeth, axes) in the case layout");
    cmd->add_option("dir", args->dir, "Case folder to write (<dir>/input/<jaw>/...)")->required();
    cmd->add_option("--teeth", args->teeth, "Teeth per jaw, nearest the midline first")
        ->check(CLI::Range(1, 16))
        ->capture_default_str();
    cmd->add_option("--seed", args->seed, "Perturbs sizes, angles and the triangulation")->capture_default_str();
    cmd->add_option("--jaw", args->jaw, "Which jaw")
        ->check(CLI::IsMember({"mandible", "maxilla", "both"}))
        ->capture_default_str();
    cmd->add_option("--triangles-scale", args->trianglesScale,
                    "Multiplies the triangle counts (< 1 for a lighter case)")
        ->check(CLI::Range(1e-3, 16.0))
        ->capture_default_str();
    cmd->add_option("--label-map", args->labelMap,
                    "Write a label volume instead of surfaces: labels.nrrd, labels.seg.nrrd (3D Slicer), labels.nii or "
                    "labels.nii.gz (with labels.json naming the labels)")
        ->check(CLI::IsMember({"labels.nrrd", "labels.seg.nrrd", "labels.nii", "labels.nii.gz"}));
    cmd->add_option("--voxel", args->voxelMm, "Voxel size of the label volume, mm")->check(CLI::Range(0.01, 2.0))->capture_default_str();
    cmd->add_option("--pdl-labels", args->pdlLabelsMm, "Label the PDL, this thick (mm), in the label volume (0 = no PDL labels)")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    cmd->callback([args, &global] { runPhantom(*args, global); });
}

}  // namespace
JAWMESH_COMMAND(10, addPhantomCommand);
}  // namespace jawmesh
