// How far carving moved each input surface, without meshing: for every vertex of the case's input
// bone and teeth, the carved region's signed distance there (trilinear on its .vdb, as written by
// `jawmesh carve` or `jawmesh run --write-levelsets`). This is the input -> output direction of #5's
// Hausdorff check before extraction and simplification add their share (about 0.02 mm near teeth).
// Prints per region the largest shift, its place, the nearest other tooth there, and the share of
// vertices moved more than 0.15 / 0.2 mm. Where the written band (the bone's is 3 voxels) is too
// narrow, the distance is taken to the zero crossings of the grid within kSearchMm.
// Usage: bench_carve_shift <levelsets folder> <case>/input/<jaw>
#include "io/Case.h"
#include "io/Error.h"
#include "levelset/JawInput.h"
#include "levelset/LabelFieldIO.h"

#include <openvdb/tools/Interpolation.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace jawmesh;
namespace fs = std::filesystem;

namespace {

constexpr double kSearchMm = 0.5;

/// Distance from p to the nearest zero crossing of grid within kSearchMm (band voxels under one
/// voxel from the surface, projected along the gradient); kSearchMm when there is none.
double distanceToZeroSet(const openvdb::FloatGrid& grid, const Vec3& p) {
    const double voxel = grid.voxelSize()[0];
    const auto& xf = grid.transform();
    const openvdb::Coord c = xf.worldToIndexCellCentered(openvdb::Vec3d(p.x(), p.y(), p.z()));
    const int r = int(std::ceil(kSearchMm / voxel));
    auto acc = grid.getConstAccessor();
    double best = kSearchMm;
    for (int i = -r; i <= r; ++i)
        for (int j = -r; j <= r; ++j)
            for (int k = -r; k <= r; ++k) {
                const openvdb::Coord q = c.offsetBy(i, j, k);
                float v;
                if (!acc.probeValue(q, v) || std::abs(v) >= voxel) continue;
                const openvdb::Vec3d g(acc.getValue(q.offsetBy(1, 0, 0)) - acc.getValue(q.offsetBy(-1, 0, 0)),
                                       acc.getValue(q.offsetBy(0, 1, 0)) - acc.getValue(q.offsetBy(0, -1, 0)),
                                       acc.getValue(q.offsetBy(0, 0, 1)) - acc.getValue(q.offsetBy(0, 0, -1)));
                if (!(g.length() > 0)) continue;
                const openvdb::Vec3d s = xf.indexToWorld(q) - double(v) * g.unit();
                best = std::min(best, (openvdb::Vec3d(p.x(), p.y(), p.z()) - s).length());
            }
    return best;
}

struct Shift {
    double maxMm = 0, bandMm = 0;
    Vec3 at{0, 0, 0};
    std::size_t vertices = 0, above15 = 0, above20 = 0;
};

Shift measure(const SurfaceMesh& input, const openvdb::FloatGrid& carved) {
    Shift s;
    s.bandMm = carved.background();
    openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(carved);
    for (const Vec3& v : input.vertices) {
        double d = std::abs(double(sampler.wsSample(openvdb::Vec3d(v.x(), v.y(), v.z()))));
        if (d > s.bandMm - 0.5 * carved.voxelSize()[0]) d = distanceToZeroSet(carved, v);
        ++s.vertices;
        s.above15 += d > 0.15;
        s.above20 += d > 0.2;
        if (d > s.maxMm) s.maxMm = d, s.at = v;
    }
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s <levelsets folder> <case>/input/<jaw>\n", argv[0]);
        return 2;
    }
    try {
        openvdb::initialize();
        const fs::path jawDir = fs::path(argv[2]).lexically_normal();
        const CaseInfo info = discoverCase(jawDir.parent_path().parent_path().string());
        const Jaw jaw = jawFromName(jawDir.filename().string());
        JawSurfaces input;
        for (const JawCase& jc : info.jaws)
            if (jc.jaw == jaw) input = loadJawInput(jc);
        const LabelField field = readLabelField(argv[1]);
        std::printf("| region | vertices | largest shift mm | at (x, y, z) | share > 0.15 / 0.2 mm | band mm |\n"
                    "|---|---|---|---|---|---|\n");
        const auto row = [&](const std::string& name, const SurfaceMesh& mesh, Label label) {
            const auto it = field.distances.find(label);
            if (it == field.distances.end()) throw Error(name + ": no carved grid in " + std::string(argv[1]));
            const Shift s = measure(mesh, *it->second);
            std::printf("| %s | %zu | %.4f | (%.2f, %.2f, %.2f) | %.5f / %.5f | %.3f |\n", name.c_str(), s.vertices, s.maxMm,
                        s.at.x(), s.at.y(), s.at.z(), double(s.above15) / double(s.vertices),
                        double(s.above20) / double(s.vertices), s.bandMm);
        };
        row("bone", input.bone, boneLabel(jaw));
        for (const auto& [unn, mesh] : input.teeth) row("tooth_" + std::to_string(unn), mesh, toothLabel(unn));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
