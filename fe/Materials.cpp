// Implements fe/Materials.h; what it computes, its rules and its contract are documented there.
#include "fe/Materials.h"

#include "io/Error.h"

#include <cmath>

namespace jawmesh {

const Material& materialOf(const MaterialTable& table, LabelKind kind) {
    switch (kind) {
    case LabelKind::Bone: return table.bone;
    case LabelKind::Tooth: return table.tooth;
    case LabelKind::Pdl: return table.pdl;
    case LabelKind::Implant: return table.implant;
    default: throw Error("no material for the outside");
    }
}

const Material& materialOf(const MaterialTable& table, Label label) {
    if (label == kOutsideLabel) throw Error("no material for label " + std::to_string(label));
    return materialOf(table, labelKind(label));
}

std::string materialName(LabelKind kind) {
    switch (kind) {
    case LabelKind::Bone: return "bone";
    case LabelKind::Tooth: return "tooth";
    case LabelKind::Pdl: return "pdl";
    case LabelKind::Implant: return "implant";
    default: throw Error("no material for the outside");
    }
}

double neoHookeC10(const Material& m) { return m.youngMpa / (4.0 * (1.0 + m.poisson)); }

double neoHookeD1(const Material& m) { return 6.0 * (1.0 - 2.0 * m.poisson) / m.youngMpa; }

void applyMaterialOverrides(const nlohmann::json& overrides, MaterialTable& table, const std::string& source) {
    if (!overrides.is_object()) throw Error(source, "materials must be an object keyed by bone | tooth | pdl | implant");
    for (const auto& [kind, values] : overrides.items()) {
        Material* m = kind == "bone" ? &table.bone : kind == "tooth" ? &table.tooth : kind == "pdl" ? &table.pdl
                    : kind == "implant" ? &table.implant : nullptr;
        if (!m) throw Error(source, "unknown material '" + kind + "' (expected bone, tooth, pdl or implant)");
        if (!values.is_object()) throw Error(source, "material '" + kind + "' must be an object with E, nu, rho");
        Material next = *m;
        for (const auto& [key, v] : values.items()) {
            if (!v.is_number()) throw Error(source, "material '" + kind + "': '" + key + "' must be a number");
            if (key == "E") next.youngMpa = v.get<double>();
            else if (key == "nu") next.poisson = v.get<double>();
            else if (key == "rho") next.densityTonnePerMm3 = v.get<double>();
            else throw Error(source, "material '" + kind + "': unknown key '" + key + "' (expected E, nu, rho)");
        }
        if (!(next.youngMpa > 0) || !std::isfinite(next.youngMpa))
            throw Error(source, "material '" + kind + "': E must be a positive number of MPa");
        if (!(next.poisson > -1.0 && next.poisson < 0.5))
            throw Error(source, "material '" + kind + "': nu must lie in (-1, 0.5)");
        if (!(next.densityTonnePerMm3 >= 0) || !std::isfinite(next.densityTonnePerMm3))
            throw Error(source, "material '" + kind + "': rho must be >= 0 (tonne/mm^3)");
        *m = next;
    }
}

nlohmann::json materialsToJson(const MaterialTable& table) {
    auto one = [](const Material& m) {
        return nlohmann::json{{"E", m.youngMpa}, {"nu", m.poisson}, {"rho", m.densityTonnePerMm3}};
    };
    return {{"bone", one(table.bone)}, {"tooth", one(table.tooth)}, {"pdl", one(table.pdl)}, {"implant", one(table.implant)}};
}

}  // namespace jawmesh
