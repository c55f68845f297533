// Implements support_LabelCase.h.
#include "support_LabelCase.h"

#include "io/Case.h"
#include "io/LabelRoles.h"
#include "io/LabelVolume.h"
#include "io/MeshIO.h"
#include "levelset/LabelVolumeSurfaces.h"
#include "tet/ElementQuality.h"

#include <filesystem>

namespace jawmesh::test {

double totalVolumeMm3(const TetMesh& mesh) {
    double total = 0;
    for (const auto& [label, volume] : labelVolumesMm3(mesh)) total += volume;
    return total;
}

void writeLabelSurfaces(const std::string& labelJawDir, const std::string& outJawDir) {
    namespace fs = std::filesystem;
    const Jaw jaw = jawFromName(fs::path(labelJawDir).filename().string());
    const std::string json = (fs::path(labelJawDir) / "labels.json").string();
    const LabelVolume v = readLabelVolume(labelVolumeIn(labelJawDir));
    const JawSurfaces s = surfacesFromLabelVolume(v, assignLabelRoles(v, jaw, fs::exists(json) ? json : ""), jaw);
    writeSurface(s.bone, (fs::path(outJawDir) / "bone" / (jawName(jaw) + ".stl")).string());
    for (const auto& [unn, tooth] : s.teeth)
        writeSurface(tooth, (fs::path(outJawDir) / "teeth" / ("tooth_" + std::to_string(unn) + ".stl")).string());
}

}  // namespace jawmesh::test
