// Implements io/LabelsJson.h; what it computes, its rules and its contract are documented there.
#include "io/LabelsJson.h"

#include "io/AtomicFile.h"
#include "io/Error.h"

#include <algorithm>
#include <ostream>

namespace jawmesh {

nlohmann::ordered_json labelsJson(const std::vector<Label>& labels) {
    std::vector<Label> distinct = labels;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    nlohmann::ordered_json entries = nlohmann::ordered_json::object();
    for (Label l : distinct) {
        nlohmann::ordered_json e;
        switch (labelKind(l)) {
        case LabelKind::Outside: throw Error("label 0 (outside) cannot appear in labels.json");
        case LabelKind::Bone:
            e["kind"] = "bone";
            e["jaw"] = jawName(l == kMandibleBoneLabel ? Jaw::Mandible : Jaw::Maxilla);
            break;
        case LabelKind::Tooth:
            e["kind"] = "tooth";
            e["tooth"] = labelUnn(l);
            break;
        case LabelKind::Pdl:
            e["kind"] = "pdl";
            e["tooth"] = labelUnn(l);
            break;
        case LabelKind::Implant:
            e["kind"] = "implant";
            e["tooth"] = labelUnn(l);
            e["material"] = "titanium";
            break;
        }
        e["name"] = labelName(l);
        entries[std::to_string(l)] = e;
    }
    nlohmann::ordered_json j;
    j["labels"] = entries;
    return j;
}

void writeLabelsJson(const std::vector<Label>& labels, const std::string& path) {
    const std::string text = labelsJson(labels).dump(2) + "\n";
    writeFileAtomically(path, [&](std::ostream& out) { out << text; }, false);
}

}  // namespace jawmesh
