// jawmesh levelset: one surface -> one narrow-band signed distance grid (.vdb).
#include "cli/Commands.h"
#include "cli/NumberChecks.h"
#include "cli/RunOptions.h"
#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/MeshIO.h"
#include "io/ResourceUsage.h"
#include "levelset/MeshToLevelSet.h"

#include <nlohmann/json.hpp>
#include <openvdb/io/File.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

namespace jawmesh {
namespace {
struct LevelsetOptions {
    std::string input;
    std::string output;
    double voxelMm = 0.0;
    double bandVoxels = defaultRunOptions().bandVoxels;  ///< `jawmesh run`'s
    bool json = false;
};

nlohmann::json coordJson(const openvdb::Coord& c) { return {c.x(), c.y(), c.z()}; }

void runLevelset(const LevelsetOptions& opt, const GlobalOptions& global) {
    const auto start = std::chrono::steady_clock::now();
    const SurfaceMesh mesh = readSurface(opt.input);
    MeshToLevelSetStats stats;
    openvdb::FloatGrid::Ptr grid = meshToLevelSet(mesh, opt.voxelMm, opt.bandVoxels, stats, terminalProgress(global));
    grid->setName(std::filesystem::path(opt.output).stem().string());
    grid->setIsInWorldSpace(true);
    writeFileAtomicallyByName(opt.output, [&](const std::string& tmp) {
        openvdb::io::File file(tmp);
        file.write({grid});
        file.close();
    });
    const double seconds = secondsSince(start);
    if (!opt.json) return;
    const openvdb::CoordBBox ib = grid->evalActiveVoxelBoundingBox();
    const openvdb::Vec3d wmin = grid->indexToWorld(ib.min()), wmax = grid->indexToWorld(ib.max());
    nlohmann::json j = {
        {"input", opt.input},
        {"output", opt.output},
        {"grid", grid->getName()},
        {"voxel_mm", opt.voxelMm},
        {"band_voxels", opt.bandVoxels},
        {"index_bbox", {{"min", coordJson(ib.min())}, {"max", coordJson(ib.max())}}},
        {"world_bbox_mm", {{"min", {wmin.x(), wmin.y(), wmin.z()}}, {"max", {wmax.x(), wmax.y(), wmax.z()}}}},
        {"seconds", seconds},
        {"peak_memory_bytes", peakResidentMemoryBytes()},
    };
    j.update(toJson(stats));
    std::cout << j.dump() << std::endl;
}

void addLevelsetCommand(CLI::App& app, GlobalOptions& global) {
    auto opt = std::make_shared<LevelsetOptions>();
    auto* cmd = app.add_subcommand(
        "levelset",
        "Surface mesh -> narrow-band signed distance grid (.vdb, one float level-set grid named after the output "
        "file stem; mm, negative inside). Dirty input is fine: holes a few voxels wide, flipped or duplicate faces, "
        "overlapping shells (their union is inside), inward-oriented cavity shells.");
    cmd->add_option("surface", opt->input, "Input surface (.stl, .obj, .ply, .off), mm")->required()->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", opt->output, "Output grid file (.vdb)")->required();
    cmd->add_option("--voxel", opt->voxelMm, "Voxel size, mm (e.g. 0.05)")->required()->default_str("")->check(positiveNumber());
    cmd->add_option("--band", opt->bandVoxels, "Narrow band half width, voxels")->check(CLI::Range(1.0, 1000.0));
    cmd->add_flag("--json", opt->json, "Print one JSON object: active voxels, bounding boxes, seconds, peak memory");
    cmd->callback([opt, &global] { runLevelset(*opt, global); });
}
}  // namespace
JAWMESH_COMMAND(20, addLevelsetCommand);
}  // namespace jawmesh
