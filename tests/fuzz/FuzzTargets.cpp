// Implements the test helpers of FuzzTargets.h (documented there).
#include "FuzzTargets.h"

#include "cli/RunOptions.h"
#include "io/Edits.h"
#include "io/Error.h"
#include "io/LabelRoles.h"
#include "io/LabelVolume.h"
#include "io/MeshIO.h"
#include "io/ToothAxes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

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

/// Writes the bytes to a file of this process with the given name ending, for readers of files.
std::string scratchFile(const std::string& bytes, const std::string& suffix) {
    const std::string path = (std::filesystem::temp_directory_path() / ("jawmesh-fuzz-" + std::to_string(::getpid()) + suffix)).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

bool readsVolume(const std::string& bytes, const std::string& suffix) {
    const std::string path = scratchFile(bytes, suffix);
    try {
        const LabelVolume v = readLabelVolume(path);
        std::filesystem::remove(path);
        std::size_t labelled = 0;
        for (const LabelSegment& s : v.segments) labelled += s.voxelCount;
        return v.values.size() == v.voxels() * static_cast<std::size_t>(v.layers) && v.directionsMm.allFinite() &&
               v.originMm.allFinite() && labelled > 0;
    } catch (const Error&) {
        std::filesystem::remove(path);
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

bool editsJson(const std::string& input) {
    const std::string path = scratchFile(input, "-edits.json");
    EditList list;
    try {
        list = readEditFile(path);
    } catch (const Error&) {
        std::filesystem::remove(path);
        return true;
    }
    std::filesystem::remove(path);
    const auto positive = [](double x) { return std::isfinite(x) && x > 0; };
    for (const Edit& edit : list.edits) {
        const bool ok = std::visit(
            [&](const auto& e) {
                using T = std::decay_t<decltype(e)>;
                if constexpr (std::is_same_v<T, BoneLossEdit>)
                    return !e.teeth.empty() && positive(e.depthMm) &&
                           std::all_of(e.teeth.begin(), e.teeth.end(), [](int u) { return isValidUnn(u); });
                else if constexpr (std::is_same_v<T, AngularDefectEdit>)
                    return isValidUnn(e.tooth) && positive(e.depthMm) && positive(e.widthMm);
                else if constexpr (std::is_same_v<T, PdlThicknessEdit>)
                    return isValidUnn(e.tooth) && positive(e.cervicalMm) && positive(e.midRootMm) && positive(e.apicalMm);
                else
                    return isValidUnn(e.tooth);
            },
            edit);
        if (!ok) return false;
    }
    return true;
}

bool nrrd(const std::string& input) { return readsVolume(input, ".nrrd"); }
bool nifti(const std::string& input) { return readsVolume(input, ".nii"); }

bool labelsJson(const std::string& input) {
    LabelVolume v;
    v.path = "fuzz volume";
    v.size = {2, 1, 1};
    v.values = {1, 124};
    v.segments = {{0, 1, "", 1}, {0, 124, "", 1}};
    const std::string path = scratchFile(input, "-labels.json");
    try {
        const LabelAssignment a = assignLabelRoles(v, Jaw::Mandible, path);
        std::filesystem::remove(path);
        return a.roles.size() == 2 && std::none_of(a.roles.begin(), a.roles.end(), [](const LabelRole& r) {
                   return (r.kind == LabelRole::Kind::Tooth || r.kind == LabelRole::Kind::Pdl) && !isValidUnn(r.unn);
               });
    } catch (const Error&) {
        std::filesystem::remove(path);
        return true;
    }
}

const std::vector<Target>& targets() {
    static const std::vector<Target> all = {{"stl_binary", stlBinary}, {"stl_ascii", stlAscii}, {"obj", obj},
                                            {"ply", ply},              {"off", off},            {"axes_json", axesJson},
                                            {"config_json", configJson}, {"nrrd", nrrd},
                                            {"nifti", nifti},          {"labels_json", labelsJson},
                                            {"edits_json", editsJson}};
    return all;
}

}  // namespace jawmesh::fuzz
