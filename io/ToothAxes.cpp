// Implements io/ToothAxes.h; what it computes, its rules and its contract are documented there.
#include "io/ToothAxes.h"

#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/Labels.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

namespace jawmesh {
namespace {

Vec3 point(const std::string& path, const std::string& key, const nlohmann::json& tooth, const char* name) {
    const auto it = tooth.find(name);
    if (it == tooth.end()) throw Error(path, "tooth " + key + ": missing \"" + name + "\"");
    if (!it->is_array() || it->size() != 3)
        throw Error(path, "tooth " + key + ": \"" + name + "\" must be an array of 3 numbers");
    Vec3 p;
    for (int i = 0; i < 3; ++i) {
        const auto& v = (*it)[static_cast<std::size_t>(i)];
        if (!v.is_number()) throw Error(path, "tooth " + key + ": \"" + name + "\" must be an array of 3 numbers");
        p[i] = v.get<double>();
    }
    if (!p.allFinite()) throw Error(path, "tooth " + key + ": \"" + name + "\" is not finite");
    return p;
}

Vec3 unitAxis(const std::string& path, const std::string& key, const nlohmann::json& tooth, const char* name,
              const Vec3& centre) {
    const Vec3 d = point(path, key, tooth, name) - centre;
    const double length = d.norm();
    if (!(length > 1e-9)) throw Error(path, "tooth " + key + ": axis \"" + name + "\" has zero length");
    // Finite end points can still be 1e308 apart: the difference overflows and would divide to NaN.
    if (!std::isfinite(length)) throw Error(path, "tooth " + key + ": axis \"" + name + "\" is too long (not finite)");
    return d / length;
}

}  // namespace

std::map<int, ToothAxes> readToothAxes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "cannot open tooth axes file");
    std::ostringstream text;
    text << in.rdbuf();
    return parseToothAxes(text.str(), path);
}

std::map<int, ToothAxes> parseToothAxes(const std::string& text, const std::string& path) {
    nlohmann::json root;
    try {
        root = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, std::string("invalid JSON: ") + e.what());
    }
    if (!root.is_object()) throw Error(path, "tooth axes must be a JSON object keyed by tooth number");
    std::map<int, ToothAxes> axes;
    for (const auto& [key, tooth] : root.items()) {
        std::size_t used = 0;
        int unn = 0;
        try {
            unn = std::stoi(key, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != key.size() || key.empty() || !isValidUnn(unn))
            throw Error(path, "key \"" + key + "\" is not a tooth number 1..32");
        if (!tooth.is_object()) throw Error(path, "tooth " + key + ": expected an object with c, x, y, z");
        ToothAxes a;
        a.crownCentre = point(path, key, tooth, "c");
        a.mesialDistal = unitAxis(path, key, tooth, "x", a.crownCentre);
        a.labial = unitAxis(path, key, tooth, "y", a.crownCentre);
        a.occlusal = unitAxis(path, key, tooth, "z", a.crownCentre);
        if (!axes.emplace(unn, a).second) throw Error(path, "tooth " + key + " appears twice");
    }
    return axes;
}

void writeToothAxes(const std::map<int, ToothAxes>& axes, const std::string& path) {
    nlohmann::json root = nlohmann::json::object();
    auto array = [](const Vec3& p) { return nlohmann::json::array({p.x(), p.y(), p.z()}); };
    for (const auto& [unn, a] : axes) {
        if (!isValidUnn(unn)) throw Error(path, "cannot write axes of invalid tooth number " + std::to_string(unn));
        if (!a.crownCentre.allFinite() || !a.mesialDistal.allFinite() || !a.labial.allFinite() || !a.occlusal.allFinite())
            throw Error(path, "cannot write non-finite axes of tooth " + std::to_string(unn));
        root[std::to_string(unn)] = {{"c", array(a.crownCentre)},
                                     {"x", array(a.crownCentre + a.mesialDistal)},
                                     {"y", array(a.crownCentre + a.labial)},
                                     {"z", array(a.crownCentre + a.occlusal)}};
    }
    const std::string text = root.dump(4) + "\n";
    writeFileAtomically(path, [&](std::ostream& out) { out << text; }, false);
}

}  // namespace jawmesh
