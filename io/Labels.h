// Region labels, identical in every output (see docs/DESIGN.md): 1 mandible bone, 2 maxilla bone,
// 100 + UNN tooth, 200 + UNN PDL, 300 + UNN implant in place of tooth UNN (a clinical edit: fused
// to the bone, no PDL). Code never does 100/200/300 arithmetic itself; it calls these.
#pragma once

#include <cstdint>
#include <string>

namespace jawmesh {

using Label = std::int32_t;

enum class Jaw { Mandible, Maxilla };

enum class LabelKind { Outside, Bone, Tooth, Pdl, Implant };

constexpr Label kOutsideLabel = 0;
constexpr Label kMandibleBoneLabel = 1;
constexpr Label kMaxillaBoneLabel = 2;

/// True for a Universal Numbering System tooth number (1..32).
constexpr bool isValidUnn(int unn) { return unn >= 1 && unn <= 32; }
/// Molars by UNN, both jaws: 1-3 and 14-16 (maxilla), 17-19 and 30-32 (mandible).
constexpr bool isMolar(int unn) { return unn <= 3 || (unn >= 14 && unn <= 19) || unn >= 30; }

Label boneLabel(Jaw jaw);
Label toothLabel(int unn);   ///< throws Error for an invalid UNN
Label pdlLabel(int unn);     ///< throws Error for an invalid UNN
Label implantLabel(int unn); ///< throws Error for an invalid UNN

LabelKind labelKind(Label label);
/// UNN of a tooth, PDL or implant label; throws Error for other labels.
int labelUnn(Label label);
/// Whether a region is rigid and load-bearing like a tooth: a tooth or an implant (crowns, the
/// interfaces' tight bounds, the teeth's element size).
inline bool isToothLike(LabelKind kind) { return kind == LabelKind::Tooth || kind == LabelKind::Implant; }
/// "bone_mandible", "bone_maxilla", "tooth_24", "pdl_24", "implant_19"; "outside" for 0. Throws for
/// unknown labels.
std::string labelName(Label label);

std::string jawName(Jaw jaw);        ///< "mandible" | "maxilla"
Jaw jawFromName(const std::string& name);  ///< throws Error for other names
/// Which jaw a tooth belongs to: UNN 1..16 maxilla, 17..32 mandible.
Jaw jawOfTooth(int unn);

}  // namespace jawmesh
