// Clinical what-if edits (issue #24) as plain data, read from an edit file:
//   {"edits": [
//     {"op": "bone_loss", "teeth": [23, 24, 25, 26], "depth_mm": 2.0},
//     {"op": "bone_loss", "tooth": 27, "side": "distal", "depth_mm": 3.0, "width_mm": 1.5},
//     {"op": "extract", "tooth": 30, "socket": "healed"},
//     {"op": "pdl_thickness", "tooth": 24, "thickness_mm": 0.3},
//     {"op": "implant", "tooth": 19, "diameter_mm": 4.1, "length_mm": 10.0}
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

/// An implant in place of a tooth (levelset/ImplantBody.h): the tooth is extracted with a healed
/// socket and a body of diameterMm x lengthMm goes in along its long axis, its platform
/// platformDepthMm below the healed crest, fused to the bone (no PDL). A screw-form body has a
/// thread of threadDepthMm (radial) and threadPitchMm; the cylinder has none. With a crown, the
/// natural tooth's crown above the platform sits on the body (one implant region, abutment and
/// crown included), so a load on the crown reaches the bone through the implant alone.
struct ImplantEdit {
    enum class Body { Cylinder, Screw };
    int tooth = 0;
    double diameterMm = 4.1, lengthMm = 10.0, platformDepthMm = 0.0;
    Body body = Body::Cylinder;
    double threadDepthMm = 0.3, threadPitchMm = 0.8;
    bool crown = true;
};

using Edit = std::variant<ExtractEdit, BoneLossEdit, AngularDefectEdit, PdlThicknessEdit, ImplantEdit>;

/// "mesial", "distal", "buccal", "lingual".
std::string sideName(AngularDefectEdit::Side side);

/// The edits of one file, in order, and the file they came from (named in messages and run.json).
struct EditList {
    std::string file;
    std::vector<Edit> edits;
};

/// Reads an edit file. Throws Error naming the file and the entry ("edits[2]") for malformed JSON,
/// an unknown op or key, a missing or invalid value (a UNN outside 1..32, a negative depth or
/// thickness, a tooth edited after it was extracted or replaced by an implant, an implant's size out
/// of range or its thread deeper than a third of its radius). Whether the teeth exist in a jaw is checked
/// when the edits are applied (requireEditsFit).
EditList readEditFile(const std::string& path);

/// readEditFile on JSON held in memory; `name` names it in messages.
EditList parseEdits(const nlohmann::json& document, const std::string& name);

/// Every tooth an edit names must be one of `teeth` (the jaw's UNNs); throws Error naming the edit
/// file and the entry otherwise. Called before any level set is built.
void requireEditsFit(const EditList& edits, const std::vector<int>& teeth);

/// The teeth extracted by the edits (no label of theirs is left in the mesh); teeth replaced by an
/// implant are not among them.
std::vector<int> extractedTeeth(const EditList& edits);

/// The teeth replaced by an implant (implantLabel in the mesh, no tooth or PDL label).
std::vector<int> implantedTeeth(const EditList& edits);

/// The edits as run.json records them: the file and each entry in its canonical form.
nlohmann::json toJson(const EditList& edits);

/// One implant edit in its canonical form (every key, defaults included).
nlohmann::json toJson(const ImplantEdit& edit);

}  // namespace jawmesh
