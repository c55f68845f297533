// Implements io/LabelRoles.h; what it computes, its rules and its contract are documented there.
#include "io/LabelRoles.h"

#include "io/Error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <set>

namespace jawmesh {
namespace {

/// Lower case without spaces, '-' and '_': "Tooth 24" and "tooth_24" both give "tooth24".
std::string squeezed(const std::string& name) {
    std::string out;
    for (unsigned char c : name)
        if (!std::isspace(c) && c != '_' && c != '-') out.push_back(static_cast<char>(std::tolower(c)));
    return out;
}

/// "<prefix><digits>" -> digits as a number, else -1.
int numberAfter(const std::string& s, const std::string& prefix) {
    if (s.size() <= prefix.size() || s.compare(0, prefix.size(), prefix) != 0 || s.size() > prefix.size() + 3) return -1;
    const std::string digits = s.substr(prefix.size());
    return digits.find_first_not_of("0123456789") == std::string::npos ? std::stoi(digits) : -1;
}

std::string describe(const LabelSegment& s) {
    return std::to_string(s.value) + (s.name.empty() ? "" : " ('" + s.name + "')") + ": " + std::to_string(s.voxelCount) + " voxels";
}

/// labels.json: value -> role, and the PDL mode.
std::map<std::int32_t, LabelRole> readLabelsJson(const std::string& path, PdlLabels& pdl) {
    std::ifstream in(path);
    if (!in) throw Error(path, "cannot open");
    nlohmann::json root;
    try {
        root = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, std::string("not valid JSON: ") + e.what());
    }
    if (!root.is_object() || !root.contains("labels") || !root["labels"].is_object())
        throw Error(path, "expected {\"labels\": {\"<value>\": \"bone\" | \"tooth_<UNN>\" | \"pdl_<UNN>\" | \"ignore\", ...}}");
    std::map<std::int32_t, LabelRole> roles;
    for (const auto& [key, value] : root["labels"].items()) {
        std::int32_t label = 0;
        try {
            std::size_t used = 0;
            label = std::stoi(key, &used);
            if (used != key.size()) throw std::invalid_argument(key);
        } catch (const std::exception&) {
            throw Error(path, "label key '" + key + "' is not an integer label value");
        }
        LabelRole role;
        if (!value.is_string() || !roleFromName(value.get<std::string>(), role))
            throw Error(path, "label " + key + ": '" + value.dump() + "' is not bone, tooth_<UNN>, pdl_<UNN> or ignore");
        roles[label] = role;
    }
    if (root.contains("pdl")) {
        const std::string mode = root["pdl"].is_string() ? root["pdl"].get<std::string>() : "";
        if (mode != "keep" && mode != "generate") throw Error(path, "\"pdl\" must be \"keep\" or \"generate\", not " + root["pdl"].dump());
        pdl = mode == "keep" ? PdlLabels::Keep : PdlLabels::Generate;
    }
    return roles;
}

void checkAssignment(const LabelVolume& volume, Jaw jaw, const LabelAssignment& a, const std::vector<bool>& named,
                     const std::string& source) {
    std::string unmapped;
    std::set<int> teeth, pdls;
    bool bone = false;
    for (std::size_t i = 0; i < a.roles.size(); ++i) {
        const LabelRole& r = a.roles[i];
        if (r.kind == LabelRole::Kind::Bone) bone = true;
        if (r.kind == LabelRole::Kind::Tooth || r.kind == LabelRole::Kind::Pdl) {
            if (!isValidUnn(r.unn) || jawOfTooth(r.unn) != jaw)
                throw Error(source, "label " + describe(volume.segments[i]) + " names tooth " + std::to_string(r.unn) +
                                        ", which is not a tooth of the " + jawName(jaw) +
                                        (jaw == Jaw::Mandible ? " (17..32)" : " (1..16)"));
            (r.kind == LabelRole::Kind::Tooth ? teeth : pdls).insert(r.unn);
        }
    }
    for (std::size_t i = 0; i < a.roles.size(); ++i)
        if (!named[i]) unmapped += "\n  " + describe(volume.segments[i]);
    if (!unmapped.empty())
        throw Error(source, "labels without a role (map them in labels.json: bone, tooth_<UNN>, pdl_<UNN> or ignore):" + unmapped);
    for (int unn : pdls)
        if (!teeth.count(unn)) throw Error(source, "a PDL label for tooth " + std::to_string(unn) + " but no label of that tooth");
    if (!bone) throw Error(source, "no label is bone");
    if (teeth.empty()) throw Error(source, "no label is a tooth");
}

}  // namespace

bool roleFromName(const std::string& name, LabelRole& role) {
    const std::string s = squeezed(name);
    if (s == "bone" || s == "mandible" || s == "maxilla" || s == "jaw" || s == "jawbone") {
        role = {LabelRole::Kind::Bone, 0};
        return true;
    }
    if (s == "ignore") {
        role = {LabelRole::Kind::Ignore, 0};
        return true;
    }
    if (const int unn = numberAfter(s, "tooth"); unn >= 0) {
        role = {LabelRole::Kind::Tooth, unn};
        return true;
    }
    if (const int unn = numberAfter(s, "pdl"); unn >= 0) {
        role = {LabelRole::Kind::Pdl, unn};
        return true;
    }
    return false;
}

LabelAssignment assignLabelRoles(const LabelVolume& volume, Jaw jaw, const std::string& labelsJsonPath) {
    LabelAssignment a;
    std::map<std::int32_t, LabelRole> fromJson;
    if (!labelsJsonPath.empty()) fromJson = readLabelsJson(labelsJsonPath, a.pdl);
    std::vector<bool> named;  // whether labels.json or the segment's name gave it a role
    for (const LabelSegment& s : volume.segments) {
        LabelRole role;
        const auto it = fromJson.find(s.value);
        if (it != fromJson.end()) role = it->second;
        named.push_back(it != fromJson.end() || roleFromName(s.name, role));
        a.hasPdl = a.hasPdl || role.kind == LabelRole::Kind::Pdl;
        a.roles.push_back(role);
    }
    checkAssignment(volume, jaw, a, named, labelsJsonPath.empty() ? volume.path : labelsJsonPath);
    return a;
}

}  // namespace jawmesh
