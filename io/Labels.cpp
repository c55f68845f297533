// Implements io/Labels.h; what it computes, its rules and its contract are documented there.
#include "io/Labels.h"

#include "io/Error.h"

namespace jawmesh {
namespace {
constexpr Label kToothBase = 100;
constexpr Label kPdlBase = 200;
constexpr Label kImplantBase = 300;

void requireUnn(int unn) {
    if (!isValidUnn(unn)) throw Error("invalid tooth number " + std::to_string(unn) + " (UNN must be 1..32)");
}
}  // namespace

Label boneLabel(Jaw jaw) { return jaw == Jaw::Mandible ? kMandibleBoneLabel : kMaxillaBoneLabel; }

Label toothLabel(int unn) {
    requireUnn(unn);
    return kToothBase + unn;
}

Label pdlLabel(int unn) {
    requireUnn(unn);
    return kPdlBase + unn;
}

Label implantLabel(int unn) {
    requireUnn(unn);
    return kImplantBase + unn;
}

LabelKind labelKind(Label label) {
    if (label == kOutsideLabel) return LabelKind::Outside;
    if (label == kMandibleBoneLabel || label == kMaxillaBoneLabel) return LabelKind::Bone;
    if (isValidUnn(label - kToothBase)) return LabelKind::Tooth;
    if (isValidUnn(label - kPdlBase)) return LabelKind::Pdl;
    if (isValidUnn(label - kImplantBase)) return LabelKind::Implant;
    throw Error("unknown region label " + std::to_string(label));
}

int labelUnn(Label label) {
    switch (labelKind(label)) {
    case LabelKind::Tooth: return label - kToothBase;
    case LabelKind::Pdl: return label - kPdlBase;
    case LabelKind::Implant: return label - kImplantBase;
    default: throw Error("label " + std::to_string(label) + " is not a tooth, PDL or implant label");
    }
}

std::string labelName(Label label) {
    switch (labelKind(label)) {
    case LabelKind::Outside: return "outside";
    case LabelKind::Bone: return label == kMandibleBoneLabel ? "bone_mandible" : "bone_maxilla";
    case LabelKind::Tooth: return "tooth_" + std::to_string(labelUnn(label));
    case LabelKind::Pdl: return "pdl_" + std::to_string(labelUnn(label));
    case LabelKind::Implant: return "implant_" + std::to_string(labelUnn(label));
    }
    return {};
}

std::string jawName(Jaw jaw) { return jaw == Jaw::Mandible ? "mandible" : "maxilla"; }

Jaw jawFromName(const std::string& name) {
    if (name == "mandible") return Jaw::Mandible;
    if (name == "maxilla") return Jaw::Maxilla;
    throw Error("unknown jaw '" + name + "' (expected mandible or maxilla)");
}

Jaw jawOfTooth(int unn) {
    requireUnn(unn);
    return unn <= 16 ? Jaw::Maxilla : Jaw::Mandible;
}

}  // namespace jawmesh
