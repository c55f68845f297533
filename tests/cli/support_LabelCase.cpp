// Implements support_LabelCase.h.
#include "support_LabelCase.h"

#include "io/Case.h"
#include "io/LabelRoles.h"
#include "io/LabelVolume.h"
#include "io/MeshIO.h"
#include "levelset/LabelVolumeSurfaces.h"
#include "tet/ElementQuality.h"

#include <cmath>
#include <filesystem>
#include <utility>

namespace jawmesh::test {

double totalVolumeMm3(const TetMesh& mesh) {
    double total = 0;
    for (const auto& [label, volume] : labelVolumesMm3(mesh)) total += volume;
    return total;
}

namespace {
std::string labelsJsonIn(const std::string& labelJawDir) {
    const std::filesystem::path json = std::filesystem::path(labelJawDir) / "labels.json";
    return std::filesystem::exists(json) ? json.string() : "";
}
}  // namespace

std::map<Label, double> labelledVolumesMm3(const std::string& labelJawDir) {
    const Jaw jaw = jawFromName(std::filesystem::path(labelJawDir).filename().string());
    const LabelVolume v = readLabelVolume(labelVolumeIn(labelJawDir));
    const LabelAssignment roles = assignLabelRoles(v, jaw, labelsJsonIn(labelJawDir));
    const double voxelMm3 = std::abs(v.directionsMm.determinant());
    std::map<Label, double> out;
    for (std::size_t i = 0; i < v.segments.size(); ++i) {
        const LabelRole& r = roles.roles[i];
        if (r.kind == LabelRole::Kind::Ignore) continue;
        const Label label = r.kind == LabelRole::Kind::Bone    ? boneLabel(jaw)
                            : r.kind == LabelRole::Kind::Tooth ? toothLabel(r.unn)
                                                               : pdlLabel(r.unn);
        out[label] += static_cast<double>(v.segments[i].voxelCount) * voxelMm3;
    }
    return out;
}

void writeLabelSurfaces(const std::string& labelJawDir, const std::string& outJawDir) {
    namespace fs = std::filesystem;
    const Jaw jaw = jawFromName(fs::path(labelJawDir).filename().string());
    LabelVolume v = readLabelVolume(labelVolumeIn(labelJawDir));
    const LabelAssignment roles = assignLabelRoles(v, jaw, labelsJsonIn(labelJawDir));
    const JawSurfaces s = surfacesFromLabelVolume(std::move(v), roles, jaw);
    writeSurface(s.bone, (fs::path(outJawDir) / "bone" / (jawName(jaw) + ".stl")).string());
    for (const auto& [unn, tooth] : s.teeth)
        writeSurface(tooth, (fs::path(outJawDir) / "teeth" / ("tooth_" + std::to_string(unn) + ".stl")).string());
}

}  // namespace jawmesh::test
