// Implements the test helpers of FuzzTargets.h (documented there).
#include "FuzzTargets.h"

#include "cli/RunOptions.h"
#include "io/Error.h"
#include "io/MeshIO.h"
#include "io/ToothAxes.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace jawmesh::fuzz {
namespace {

/// Every triangle indexes an existing vertex and every coordinate is finite.
bool validSurface(const SurfaceMesh& m) {
    if (m.triangles.empty()) return false;
    for (const Tri& t : m.triangles)
        for (std::int32_t v : t)
            if (v < 0 || static_cast<std::size_t>(v) >= m.vertices.size()) return false;
    for (const Vec3& v : m.vertices)
        if (!v.allFinite()) return false;
    return true;
}

bool readsSurface(const std::string& bytes, const std::string& name) {
    try {
        return validSurface(readSurfaceFromMemory(bytes, name));
    } catch (const Error&) {
        return true;
    }
}

}  // namespace

bool stlBinary(const std::string& input) {
    std::string bytes = input;
    if (bytes.size() >= 84) {
        const std::uint32_t count = static_cast<std::uint32_t>((bytes.size() - 84) / 50);
        bytes.resize(84 + 50 * std::size_t(count));
        std::memcpy(bytes.data() + 80, &count, 4);
    }
    return readsSurface(bytes, "fuzz.stl");
}

bool stlAscii(const std::string& input) { return readsSurface("solid " + input, "fuzz.stl"); }
bool obj(const std::string& input) { return readsSurface(input, "fuzz.obj"); }
bool ply(const std::string& input) { return readsSurface(input, "fuzz.ply"); }
bool off(const std::string& input) { return readsSurface(input, "fuzz.off"); }

bool axesJson(const std::string& input) {
    try {
        for (const auto& [unn, a] : parseToothAxes(input, "fuzz.json")) {
            if (unn < 1 || unn > 32 || !a.crownCentre.allFinite()) return false;
            for (const Vec3* axis : {&a.mesialDistal, &a.labial, &a.occlusal})
                if (!axis->allFinite() || std::abs(axis->norm() - 1.0) > 1e-9) return false;
        }
    } catch (const Error&) {
    }
    return true;
}

bool configJson(const std::string& input) {
    RunOptions options = defaultRunOptions();
    try {
        applyRunConfigText(input, "fuzz.json", options);
    } catch (const Error&) {
        return true;
    }
    return options.voxelSizeMm > 0 && options.bandVoxels >= 1 && options.carve.pdlRatio >= 0 && options.carve.pdlRatio <= 1;
}


const std::vector<Target>& targets() {
    static const std::vector<Target> all = {{"stl_binary", stlBinary}, {"stl_ascii", stlAscii}, {"obj", obj},
                                            {"ply", ply},              {"off", off},            {"axes_json", axesJson},
                                            {"config_json", configJson}};
    return all;
}

}  // namespace jawmesh::fuzz
