// The distance part of `jawmesh eval` on real anatomy without a tet mesh: two-sided distances
// between region surfaces (e.g. `jawmesh surface`'s regions/*.ply, which are what the tet mesh's
// region boundaries will be) and the case's input surfaces, with the same calls and options as
// tet/EvaluateMesh (one group per domain). Prints per-domain Hausdorff/mean and the seconds, and
// each direction's maximum with where it is (output -> input, then input -> output) and the share of
// the area farther than 0.15 / 0.25 mm. Region files: regions/<name>.ply or surface_meshes/<name>.stl
// (bone as bone_<jaw>.ply or bone.stl).
// Usage: bench_eval_distance <regions folder> <case>/input/<jaw> [spacing_mm] [tolerance_mm]
#include "filters/SurfaceDistance.h"
#include "io/Case.h"
#include "io/Error.h"
#include "io/MeshIO.h"
#include "levelset/JawInput.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

using namespace jawmesh;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s <regions folder> <case>/input/<jaw> [spacing_mm] [tolerance_mm]\n", argv[0]);
        return 2;
    }
    const double spacing = argc > 3 ? std::stod(argv[3]) : 0.2, tolerance = argc > 4 ? std::stod(argv[4]) : 0.002;
    try {
        const fs::path regions = argv[1], jawDir = fs::path(argv[2]).lexically_normal();
        const CaseInfo info = discoverCase(jawDir.parent_path().parent_path().string());
        const Jaw jaw = jawFromName(jawDir.filename().string());
        JawSurfaces input;
        for (const JawCase& jc : info.jaws)
            if (jc.jaw == jaw) input = loadJawInput(jc);
        const auto clock = [] { return std::chrono::steady_clock::now(); };
        double total = 0;
        std::size_t outTris = 0, inTris = 0;
        std::printf("| domain | output triangles | input triangles | Hausdorff mm | mean mm | out->in max at | in->out max at | "
                    "area > 0.15 / 0.25 mm (out->in, in->out) | seconds |\n|---|---|---|---|---|---|---|---|---|\n");
        const auto areaAbove = [](const DistanceSamples& d, double mm) {
            double above = 0, all = 0;
            for (std::size_t i = 0; i < d.distanceMm.size(); ++i) {
                all += d.weightMm2[i];
                if (d.distanceMm[i] > mm) above += d.weightMm2[i];
            }
            return all > 0 ? above / all : 0.0;
        };
        const auto measure = [&](const std::string& name, const SurfaceMesh& out, const SurfaceMesh& in) {
            const auto start = clock();
            std::vector<double> phase;
            auto lap = clock();
            const auto mark = [&] { phase.push_back(std::chrono::duration<double>(clock() - lap).count()); lap = clock(); };
            const TriangleBvh outBvh = buildTriangleBvh(out), inBvh = buildTriangleBvh(in);
            mark();
            const DistanceSamples a = sampleDistances(out, inBvh, spacing);
            mark();
            const DistanceSamples b = sampleDistances(in, outBvh, spacing);
            mark();
            const DistanceSummary sa = summarizeDistances(out, a, std::vector<int>(out.triangles.size(), 0), 1, inBvh, tolerance).front();
            mark();
            const DistanceSummary sb = summarizeDistances(in, b, std::vector<int>(in.triangles.size(), 0), 1, outBvh, tolerance).front();
            mark();
            if (std::getenv("BENCH_PHASES"))
                std::fprintf(stderr, "%s: bvh %.2f, sample out %.2f (%zu), sample in %.2f (%zu), max out %.2f, max in %.2f s\n", name.c_str(),
                             phase[0], phase[1], a.distanceMm.size(), phase[2], b.distanceMm.size(), phase[3], phase[4]);
            const double seconds = std::chrono::duration<double>(clock() - start).count();
            total += seconds;
            outTris += out.triangles.size();
            inTris += in.triangles.size();
            const double mean = (sa.distance.mean * sa.areaMm2 + sb.distance.mean * sb.areaMm2) / (sa.areaMm2 + sb.areaMm2);
            std::printf("| %s | %zu | %zu | %.4f | %.4f | %.4f at (%.2f, %.2f, %.2f) | %.4f at (%.2f, %.2f, %.2f) | "
                        "%.2e / %.2e, %.2e / %.2e | %.2f |\n",
                        name.c_str(), out.triangles.size(), in.triangles.size(), std::max(sa.distance.max, sb.distance.max), mean,
                        sa.distance.max, sa.maxAt.x(), sa.maxAt.y(), sa.maxAt.z(), sb.distance.max, sb.maxAt.x(), sb.maxAt.y(),
                        sb.maxAt.z(), areaAbove(a, 0.15), areaAbove(a, 0.25), areaAbove(b, 0.15), areaAbove(b, 0.25), seconds);
        };
        const auto regionFile = [&](const std::vector<std::string>& names) {
            for (const auto& n : names)
                for (const char* ext : {".ply", ".stl"})
                    if (fs::exists(regions / (n + ext))) return regions / (n + ext);
            return fs::path();
        };
        const fs::path boneFile = regionFile({"bone_" + jawName(jaw), "bone"});
        if (boneFile.empty()) throw Error(regions.string(), "no bone_<jaw>.ply or bone.stl");
        measure("bone", readSurface(boneFile.string()), input.bone);
        for (const auto& [unn, tooth] : input.teeth) {
            const fs::path file = regionFile({"tooth_" + std::to_string(unn)});
            if (!file.empty()) measure("tooth_" + std::to_string(unn), readSurface(file.string()), tooth);
        }
        std::printf("\ntotal: %.2f s for %zu output and %zu input triangles (spacing %.3f mm, tolerance %.4f mm)\n", total, outTris, inTris,
                    spacing, tolerance);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
