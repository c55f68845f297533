// Material parameters per region kind (docs/DESIGN.md, "FE scenarios"): neo-Hookean in the
// mm–N–MPa–tonne/mm^3 system, defaults of the published Open-Full-Jaw setup, overridable by JSON.
#pragma once

#include "io/Labels.h"

#include <nlohmann/json.hpp>

#include <string>

namespace jawmesh {

/// An isotropic neo-Hookean material.
struct Material {
    double youngMpa = 0;             ///< E, MPa (N/mm^2)
    double poisson = 0;              ///< nu, in (-1, 0.5)
    double densityTonnePerMm3 = 0;   ///< rho, tonne/mm^3 (consistent with mm, N, s)
};

/// One material per region kind; every tooth shares `tooth`, every PDL `pdl`, every implant
/// `implant` (titanium: E 110 GPa, nu 0.35, 4.43 g/cm^3; its crown and abutment too).
struct MaterialTable {
    Material bone{1500.0, 0.3, 1.178e-9};
    Material tooth{2000.0, 0.3, 2.18e-9};
    Material pdl{68.9, 0.45, 1.142e-9};
    Material implant{110000.0, 0.35, 4.43e-9};
};

/// The material of a region kind (bone, tooth, PDL or implant). Throws Error for the outside.
const Material& materialOf(const MaterialTable& table, LabelKind kind);

/// The material of a region label (bone of either jaw, tooth, PDL or implant). Throws Error for label 0.
const Material& materialOf(const MaterialTable& table, Label label);

/// Name of a material in decks: "bone", "tooth", "pdl", "implant".
std::string materialName(LabelKind kind);

/// Neo-Hookean constants in the Abaqus/CalculiX form W = C10 (I1 - 3) + (J - 1)^2 / D1:
/// C10 = E / (4 (1 + nu)) (MPa), D1 = 6 (1 - 2 nu) / E (1/MPa), i.e. mu / 2 and 2 / K.
double neoHookeC10(const Material& m);
double neoHookeD1(const Material& m);

/// Applies overrides such as {"pdl": {"E": 50, "nu": 0.45, "rho": 1.1e-9}, "bone": {"E": 1200}}
/// (keys bone | tooth | pdl | implant; inner keys E, nu, rho, each optional). `source` names the file in
/// errors. Throws Error for unknown keys, non-numbers, E <= 0, nu outside (-1, 0.5) or rho < 0.
void applyMaterialOverrides(const nlohmann::json& overrides, MaterialTable& table, const std::string& source);

/// The table as JSON in the same shape (for run.json and summaries).
nlohmann::json materialsToJson(const MaterialTable& table);

}  // namespace jawmesh
