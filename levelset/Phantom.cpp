// Implements levelset/Phantom.h; what it computes, its rules and its contract are documented there.
#include "levelset/Phantom.h"

#include "io/Error.h"
#include "io/MeshIO.h"
#include "levelset/PhantomAnatomy.h"
#include "levelset/LevelSetSurface.h"
#include "levelset/PhantomSurface.h"

#include <cmath>
#include <filesystem>
#include <regex>
#include <set>

namespace jawmesh {
namespace {
constexpr double kBaseVoxelMm = 0.35;
constexpr double kJitterVoxels = 0.2;  // tangential jitter amplitude

std::uint64_t meshSeed(std::uint32_t seed, Jaw jaw, int unn) {
    return (static_cast<std::uint64_t>(seed) << 32) ^ (static_cast<std::uint64_t>(jaw == Jaw::Maxilla) << 16) ^
           static_cast<std::uint64_t>(unn);
}

// One surface of the phantom: the template field sampled in the world frame, extracted, jittered.
SurfaceMesh makeSurface(const phantom::JawAnatomy& an, const std::function<double(const Vec3&)>& templateField,
                        const BBox& templateBox, double voxel, std::uint64_t seed) {
    auto world = [&](const Vec3& p) { return templateField(phantom::toTemplate(an, p)); };
    BBox box = phantom::toWorld(an, templateBox);
    box.min -= Vec3::Constant(2 * voxel);
    box.max += Vec3::Constant(2 * voxel);
    const auto grid = phantom::sampleLevelSet(world, box, voxel);
    SurfaceMesh mesh = extractLevelSetSurface(*grid);
    phantom::jitterTangentially(mesh, kJitterVoxels * voxel, seed);
    return mesh;
}
}  // namespace

PhantomJaw makePhantom(const PhantomOptions& options, Progress& progress) {
    if (!(options.trianglesScale > 0 && options.trianglesScale <= 16))
        throw Error("phantom: --triangles-scale must be in (0, 16], got " + std::to_string(options.trianglesScale));
    const phantom::JawAnatomy an = phantom::buildJawAnatomy(options.jaw, options.teeth, options.seed);
    const double voxel = kBaseVoxelMm / std::sqrt(options.trianglesScale);

    ProgressStage stage(progress, "phantom " + jawName(options.jaw));
    PhantomJaw out;
    out.jaw = options.jaw;
    out.voxelSizeMm = voxel;
    const double total = static_cast<double>(an.teeth.size()) + 4.0;  // the bone costs about 4 teeth
    double done = 0;
    for (const phantom::ToothSpec& tooth : an.teeth) {
        progress.checkCancelled();
        out.teeth[tooth.unn] = makeSurface(
            an, [&](const Vec3& p) { return phantom::toothField(tooth, p); }, tooth.box, voxel,
            meshSeed(options.seed, options.jaw, tooth.unn));
        out.axes[tooth.unn] = phantom::toothAxes(an, tooth);
        stage.update(++done / total);
    }
    progress.checkCancelled();
    out.bone = makeSurface(
        an, [&](const Vec3& p) { return phantom::boneField(an, p); }, an.boneBox, voxel,
        meshSeed(options.seed, options.jaw, 0));
    stage.update(1.0);
    return out;
}

void writePhantomCase(const std::vector<PhantomJaw>& jaws, const std::string& caseDir) {
    namespace fs = std::filesystem;
    std::set<Jaw> seen;
    for (const PhantomJaw& jaw : jaws)
        if (!seen.insert(jaw.jaw).second) throw Error(caseDir, "phantom: the " + jawName(jaw.jaw) + " is given twice");
    for (const PhantomJaw& jaw : jaws) {
        const std::string name = jawName(jaw.jaw);
        const fs::path dir = fs::path(caseDir) / "input" / name;
        const fs::path teethDir = dir / "teeth";
        std::error_code ec;
        if (fs::is_directory(teethDir, ec)) {
            const std::regex toothFile(R"(tooth_(\d{1,3})\.(stl|obj|ply|off))", std::regex::icase);
            for (const auto& entry : fs::directory_iterator(teethDir)) {
                std::smatch m;
                const std::string file = entry.path().filename().string();
                if (std::regex_match(file, m, toothFile) && !jaw.teeth.count(std::stoi(m[1].str())))
                    throw Error(entry.path().string(),
                                "not part of the phantom being written; write the phantom to an empty folder");
            }
        }
        writeSurface(jaw.bone, (dir / "bone" / (name + ".stl")).string());
        for (const auto& [unn, mesh] : jaw.teeth)
            writeSurface(mesh, (teethDir / ("tooth_" + std::to_string(unn) + ".stl")).string());
        writeToothAxes(jaw.axes, (dir / ("teeth_axes_" + name + ".json")).string());
    }
}

}  // namespace jawmesh
