// Implements io/Edits.h; what it computes, its rules and its contract are documented there.
#include "io/Edits.h"

#include "io/Error.h"
#include "io/Labels.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace jawmesh {
namespace {

/// One entry being read: its place in the file for messages, and the keys it has used up.
struct Entry {
    const nlohmann::json& json;
    std::string where;  ///< "<file>: edits[i] (op)"
    std::set<std::string> used{"op"};

    [[noreturn]] void fail(const std::string& why) const { throw Error(where + ": " + why); }

    const nlohmann::json& key(const std::string& name) {
        if (!json.contains(name)) fail("'" + name + "' is missing");
        used.insert(name);
        return json.at(name);
    }
    double number(const std::string& name, double lo, double hi) {
        const auto& v = key(name);
        if (!v.is_number()) fail("'" + name + "' must be a number");
        const double x = v.get<double>();
        if (!std::isfinite(x) || x <= lo || x > hi) {
            std::ostringstream s;
            s << "'" << name << "' is " << x << "; it must be > " << lo << " and <= " << hi;
            fail(s.str());
        }
        return x;
    }
    int tooth(const nlohmann::json& v) const {
        if (!v.is_number_integer() || !isValidUnn(v.get<int>())) fail("a tooth must be a UNN from 1 to 32");
        return v.get<int>();
    }
    /// Unknown keys are refused: a misspelt "depth_mm" must not fall back to a default.
    void requireAllUsed() const {
        for (const auto& [k, v] : json.items())
            if (!used.count(k)) fail("unknown key '" + k + "'");
    }
};

/// Thickest PDL an edit may ask for: a "PDL" wider than this is a gap, not a ligament.
constexpr double kMaxPdlMm = 2.0;
/// Deepest bone loss: more than a root is long.
constexpr double kMaxBoneLossMm = 20.0;

Edit readExtract(Entry& e) {
    ExtractEdit x;
    x.tooth = e.tooth(e.key("tooth"));
    if (e.json.contains("socket")) {
        const auto& s = e.key("socket");
        if (s != "empty" && s != "healed") e.fail("'socket' must be \"empty\" or \"healed\"");
        x.healed = s == "healed";
    }
    return x;
}

/// Widest angular defect: a funnel wider than this is a horizontal loss.
constexpr double kMaxDefectWidthMm = 5.0;

Edit readAngularDefect(Entry& e) {
    AngularDefectEdit x;
    x.tooth = e.tooth(e.key("tooth"));
    const auto& side = e.key("side");
    bool known = false;
    for (auto s : {AngularDefectEdit::Side::Mesial, AngularDefectEdit::Side::Distal, AngularDefectEdit::Side::Buccal,
                   AngularDefectEdit::Side::Lingual})
        if (side == sideName(s)) x.side = s, known = true;
    if (!known) e.fail("'side' must be \"mesial\", \"distal\", \"buccal\" or \"lingual\"");
    x.depthMm = e.number("depth_mm", 0, kMaxBoneLossMm);
    x.widthMm = e.number("width_mm", 0, kMaxDefectWidthMm);
    return x;
}

Edit readBoneLoss(Entry& e) {
    if (e.json.contains("tooth") || e.json.contains("side")) return readAngularDefect(e);
    BoneLossEdit x;
    const auto& teeth = e.key("teeth");
    if (!teeth.is_array() || teeth.empty())
        e.fail("'teeth' must be a non-empty list of UNNs (or, for an angular defect, 'tooth' and 'side')");
    for (const auto& t : teeth) x.teeth.push_back(e.tooth(t));
    std::sort(x.teeth.begin(), x.teeth.end());
    if (std::adjacent_find(x.teeth.begin(), x.teeth.end()) != x.teeth.end()) e.fail("'teeth' names a tooth twice");
    x.depthMm = e.number("depth_mm", 0, kMaxBoneLossMm);
    return x;
}

Edit readPdlThickness(Entry& e) {
    PdlThicknessEdit x;
    x.tooth = e.tooth(e.key("tooth"));
    const bool uniform = e.json.contains("thickness_mm");
    const bool profile = e.json.contains("profile_mm");
    if (uniform == profile) e.fail("give either 'thickness_mm' or 'profile_mm' ({\"cervical\", \"mid_root\", \"apical\"})");
    if (uniform) {
        x.cervicalMm = x.midRootMm = x.apicalMm = e.number("thickness_mm", 0, kMaxPdlMm);
        return x;
    }
    const auto& p = e.key("profile_mm");
    if (!p.is_object()) e.fail("'profile_mm' must be an object {\"cervical\", \"mid_root\", \"apical\"}");
    Entry inner{p, e.where + " profile_mm"};
    x.cervicalMm = inner.number("cervical", 0, kMaxPdlMm);
    x.midRootMm = inner.number("mid_root", 0, kMaxPdlMm);
    x.apicalMm = inner.number("apical", 0, kMaxPdlMm);
    inner.requireAllUsed();
    return x;
}

/// Implant sizes, mm: narrow (mini) to wide molar implants, short to long.
constexpr double kMinImplantDiameterMm = 1.5, kMaxImplantDiameterMm = 8.0;
constexpr double kMinImplantLengthMm = 3.0, kMaxImplantLengthMm = 20.0;
constexpr double kMaxPlatformDepthMm = 5.0;

std::string bodyName(ImplantEdit::Body body) { return body == ImplantEdit::Body::Screw ? "screw" : "cylinder"; }

Edit readImplant(Entry& e) {
    ImplantEdit x;
    x.tooth = e.tooth(e.key("tooth"));
    x.diameterMm = e.number("diameter_mm", kMinImplantDiameterMm, kMaxImplantDiameterMm);
    x.lengthMm = e.number("length_mm", kMinImplantLengthMm, kMaxImplantLengthMm);
    if (e.json.contains("platform_depth_mm")) {
        const auto& v = e.key("platform_depth_mm");
        if (!v.is_number() || v.get<double>() < 0 || v.get<double>() > kMaxPlatformDepthMm)
            e.fail("'platform_depth_mm' must be a number from 0 to " + std::to_string(int(kMaxPlatformDepthMm)));
        x.platformDepthMm = v.get<double>();
    }
    if (e.json.contains("body")) {
        const auto& b = e.key("body");
        if (b != "cylinder" && b != "screw") e.fail("'body' must be \"cylinder\" or \"screw\"");
        x.body = b == "screw" ? ImplantEdit::Body::Screw : ImplantEdit::Body::Cylinder;
    }
    if (x.body == ImplantEdit::Body::Screw) {
        if (e.json.contains("thread_depth_mm")) x.threadDepthMm = e.number("thread_depth_mm", 0, x.diameterMm / 6);
        if (e.json.contains("thread_pitch_mm")) x.threadPitchMm = e.number("thread_pitch_mm", 0.2, 3.0);
        if (x.threadDepthMm > x.diameterMm / 6) e.fail("the thread is deeper than a third of the radius");
    }
    if (e.json.contains("crown")) {
        const auto& c = e.key("crown");
        if (c != "tooth" && c != "none") e.fail("'crown' must be \"tooth\" (the natural crown on the implant) or \"none\"");
        x.crown = c == "tooth";
    }
    return x;
}

/// The UNNs an edit names.
std::vector<int> teethOf(const Edit& edit) {
    return std::visit(
        [](const auto& e) -> std::vector<int> {
            if constexpr (std::is_same_v<std::decay_t<decltype(e)>, BoneLossEdit>) return e.teeth;
            else return {e.tooth};
        },
        edit);
}

std::string entryName(const std::string& file, std::size_t i) { return file + ": edits[" + std::to_string(i) + "]"; }

}  // namespace

std::string sideName(AngularDefectEdit::Side side) {
    switch (side) {
        case AngularDefectEdit::Side::Mesial: return "mesial";
        case AngularDefectEdit::Side::Distal: return "distal";
        case AngularDefectEdit::Side::Buccal: return "buccal";
        case AngularDefectEdit::Side::Lingual: return "lingual";
    }
    return "";
}

EditList parseEdits(const nlohmann::json& document, const std::string& name) {
    if (!document.is_object() || !document.contains("edits") || !document.at("edits").is_array())
        throw Error(name, "an edit file is {\"edits\": [ ... ]}");
    for (const auto& [k, v] : document.items())
        if (k != "edits") throw Error(name, "unknown key '" + k + "' (an edit file holds only \"edits\")");
    EditList list{name, {}};
    std::set<int> extracted, implanted;
    const auto& edits = document.at("edits");
    for (std::size_t i = 0; i < edits.size(); ++i) {
        const auto& j = edits[i];
        if (!j.is_object() || !j.contains("op") || !j.at("op").is_string())
            throw Error(entryName(name, i) + ": each edit is an object with an \"op\"");
        const std::string op = j.at("op").get<std::string>();
        Entry e{j, entryName(name, i) + " (" + op + ")"};
        Edit edit;
        if (op == "extract") edit = readExtract(e);
        else if (op == "bone_loss") edit = readBoneLoss(e);
        else if (op == "pdl_thickness") edit = readPdlThickness(e);
        else if (op == "implant") edit = readImplant(e);
        else e.fail("unknown op (extract, bone_loss, pdl_thickness, implant)");
        e.requireAllUsed();
        for (int unn : teethOf(edit)) {
            if (extracted.count(unn)) e.fail("tooth " + std::to_string(unn) + " was extracted by an earlier edit");
            if (implanted.count(unn)) e.fail("tooth " + std::to_string(unn) + " was replaced by an implant by an earlier edit");
        }
        if (const auto* x = std::get_if<ExtractEdit>(&edit)) extracted.insert(x->tooth);
        if (const auto* x = std::get_if<ImplantEdit>(&edit)) implanted.insert(x->tooth);
        list.edits.push_back(std::move(edit));
    }
    return list;
}

EditList readEditFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path, "cannot open the edit file");
    nlohmann::json document;
    try {
        document = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, std::string("not valid JSON: ") + e.what());
    }
    return parseEdits(document, path);
}

void requireEditsFit(const EditList& edits, const std::vector<int>& teeth) {
    for (std::size_t i = 0; i < edits.edits.size(); ++i)
        for (int unn : teethOf(edits.edits[i]))
            if (std::find(teeth.begin(), teeth.end(), unn) == teeth.end())
                throw Error(entryName(edits.file, i) + ": tooth " + std::to_string(unn) + " is not in this jaw");
}

std::vector<int> extractedTeeth(const EditList& edits) {
    std::vector<int> out;
    for (const Edit& edit : edits.edits)
        if (const auto* x = std::get_if<ExtractEdit>(&edit)) out.push_back(x->tooth);
    return out;
}

std::vector<int> implantedTeeth(const EditList& edits) {
    std::vector<int> out;
    for (const Edit& edit : edits.edits)
        if (const auto* x = std::get_if<ImplantEdit>(&edit)) out.push_back(x->tooth);
    return out;
}

nlohmann::json toJson(const ImplantEdit& e) {
    nlohmann::json j = {{"op", "implant"},          {"tooth", e.tooth},
                        {"diameter_mm", e.diameterMm}, {"length_mm", e.lengthMm},
                        {"platform_depth_mm", e.platformDepthMm}, {"body", bodyName(e.body)},
                        {"crown", e.crown ? "tooth" : "none"}};
    if (e.body == ImplantEdit::Body::Screw) {
        j["thread_depth_mm"] = e.threadDepthMm;
        j["thread_pitch_mm"] = e.threadPitchMm;
    }
    return j;
}

nlohmann::json toJson(const EditList& edits) {
    nlohmann::json list = nlohmann::json::array();
    for (const Edit& edit : edits.edits)
        std::visit(
            [&](const auto& e) {
                using T = std::decay_t<decltype(e)>;
                if constexpr (std::is_same_v<T, ExtractEdit>)
                    list.push_back({{"op", "extract"}, {"tooth", e.tooth}, {"socket", e.healed ? "healed" : "empty"}});
                else if constexpr (std::is_same_v<T, BoneLossEdit>)
                    list.push_back({{"op", "bone_loss"}, {"teeth", e.teeth}, {"depth_mm", e.depthMm}});
                else if constexpr (std::is_same_v<T, AngularDefectEdit>)
                    list.push_back({{"op", "bone_loss"},
                                    {"tooth", e.tooth},
                                    {"side", sideName(e.side)},
                                    {"depth_mm", e.depthMm},
                                    {"width_mm", e.widthMm}});
                else if constexpr (std::is_same_v<T, ImplantEdit>)
                    list.push_back(toJson(e));
                else
                    list.push_back({{"op", "pdl_thickness"},
                                    {"tooth", e.tooth},
                                    {"profile_mm", {{"cervical", e.cervicalMm}, {"mid_root", e.midRootMm}, {"apical", e.apicalMm}}}});
            },
            edit);
    return {{"file", edits.file}, {"edits", list}};
}

}  // namespace jawmesh
