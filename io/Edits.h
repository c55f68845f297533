// Clinical what-if edits (issue #24) as plain data, read from an edit file:
//   {"edits": [
//     {"op": "bone_loss", "teeth": [23, 24, 25, 26], "depth_mm": 2.0},
//     {"op": "bone_loss", "tooth": 27, "side": "distal", "depth_mm": 3.0, "width_mm": 1.5},
//     {"op": "extract", "tooth": 30, "socket": "healed"},
//     {"op": "pdl_thickness", "tooth": 24, "thickness_mm": 0.3}
//   ]}
// Edits apply in order to the jaw's level sets before carving (levelset/JawEdits.h), so the carve
// restores its invariants (teeth apart, a PDL between every root and the bone, the cap at the crest)
// on the edited anatomy. Lengths in mm.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace jawmesh {

/// Remove a tooth and its PDL. The socket stays empty, or heals: bone fills it up to the crest.
struct ExtractEdit {
    int tooth = 0;
    bool healed = false;
};

/// Horizontal bone loss: the crest around each tooth lowered by depthMm along the tooth's long axis.
struct BoneLossEdit {
    std::vector<int> teeth;
    double depthMm = 0;
};

/// An angular (vertical) defect: on one side of a root the crest drops by depthMm at the root,
/// rising to none widthMm away from it (a funnel along the root).
struct AngularDefectEdit {
    enum class Side { Mesial, Distal, Buccal, Lingual };
    int tooth = 0;
    Side side = Side::Mesial;
    double depthMm = 0, widthMm = 0;
};

/// A tooth's PDL thickness, uniform or as a cervical / mid-root / apical profile (mm).
struct PdlThicknessEdit {
    int tooth = 0;
    double cervicalMm = 0, midRootMm = 0, apicalMm = 0;
};

using Edit = std::variant<ExtractEdit, BoneLossEdit, AngularDefectEdit, PdlThicknessEdit>;

/// "mesial", "distal", "buccal", "lingual".
std::string sideName(AngularDefectEdit::Side side);

/// The edits of one file, in order, and the file they came from (named in messages and run.json).
struct EditList {
    std::string file;
    std::vector<Edit> edits;
};

/// Reads an edit file. Throws Error naming the file and the entry ("edits[2]") for malformed JSON,
/// an unknown op or key, a missing or invalid value (a UNN outside 1..32, a negative depth or
/// thickness, a tooth edited after it was extracted). Whether the teeth exist in a jaw is checked
/// when the edits are applied (requireEditsFit).
EditList readEditFile(const std::string& path);

/// readEditFile on JSON held in memory; `name` names it in messages.
EditList parseEdits(const nlohmann::json& document, const std::string& name);

/// Every tooth an edit names must be one of `teeth` (the jaw's UNNs); throws Error naming the edit
/// file and the entry otherwise. Called before any level set is built.
void requireEditsFit(const EditList& edits, const std::vector<int>& teeth);

/// The teeth extracted by the edits (no label of theirs is left in the mesh).
std::vector<int> extractedTeeth(const EditList& edits);

/// The edits as run.json records them: the file and each entry in its canonical form.
nlohmann::json toJson(const EditList& edits);

}  // namespace jawmesh
