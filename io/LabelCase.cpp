// Implements io/LabelCase.h; what it computes, its rules and its contract are documented there.
#include "io/LabelCase.h"

#include "io/AtomicFile.h"
#include "io/LabelRoles.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace jawmesh {

void nameSegmentsByLabel(std::vector<LabelSegment>& segments, Jaw jaw) {
    for (LabelSegment& s : segments) {
        const LabelKind kind = labelKind(s.value);
        s.name = kind == LabelKind::Bone ? jawName(jaw) : labelName(s.value);
    }
}

void writeLabelCase(const LabelVolume& volume, Jaw jaw, const std::map<int, ToothAxes>& axes, const std::string& caseDir,
                    const std::string& fileName) {
    const std::filesystem::path dir = std::filesystem::path(caseDir) / "input" / jawName(jaw);
    const bool slicer = fileName.size() > 9 && fileName.compare(fileName.size() - 9, 9, ".seg.nrrd") == 0;
    writeLabelVolume(volume, (dir / fileName).string(), slicer);
    if (!slicer) {
        nlohmann::json labels = nlohmann::json::object();
        for (const LabelSegment& s : volume.segments) {
            LabelRole role;
            const bool named = roleFromName(s.name, role);
            labels[std::to_string(s.value)] = !named ? "ignore"
                                              : role.kind == LabelRole::Kind::Bone  ? "bone"
                                              : role.kind == LabelRole::Kind::Tooth ? "tooth_" + std::to_string(role.unn)
                                              : role.kind == LabelRole::Kind::Pdl   ? "pdl_" + std::to_string(role.unn)
                                                                                    : "ignore";
        }
        const nlohmann::json root = {{"labels", labels}};
        writeFileAtomically((dir / "labels.json").string(), [&](std::ostream& out) { out << root.dump(2) << "\n"; }, false);
    }
    if (!axes.empty()) writeToothAxes(axes, (dir / ("teeth_axes_" + jawName(jaw) + ".json")).string());
}

}  // namespace jawmesh
