// The error bound of each interface (label pair) against the fine interface, mm: what the adaptive
// extraction (AdaptiveCells.h) and the simplification (SimplifyInterfaces.h) may spend, and the
// longest edge either may make there. One place, so
// that both read the same figures (the simplification's options are the source: boundsOf there).
#pragma once

#include "io/Labels.h"

#include <algorithm>

namespace jawmesh {

struct InterfaceBounds {
    double toothErrorMm = 0.02;    ///< tooth / outside and the crest cap (PDL / outside)
    double pdlErrorMm = 0.02;      ///< tooth / PDL and PDL / bone
    double boneErrorMm = 0.08;     ///< bone / outside near a tooth or PDL
    double boneFarErrorMm = 0.15;  ///< bone / outside farther away (at least boneErrorMm)
    /// Longest edge of a triangle on tooth / PDL and PDL / bone, on the crest cap (PDL / outside),
    /// on the crowns (tooth / outside) and on the bone (bone / outside), mm.
    double pdlMaxEdgeMm = 0.4, capMaxEdgeMm = 0.065, toothMaxEdgeMm = 1.0, boneMaxEdgeMm = 2.5;

    /// The bound of interface (a, b); nearTeeth only matters on bone / outside.
    double boundMm(Label a, Label b, bool nearTeeth) const {
        switch (kindOf(a, b)) {
            case Kind::Cap: return toothErrorMm;
            case Kind::Pdl: return pdlErrorMm;
            case Kind::Tooth: return toothErrorMm;
            case Kind::Bone: break;
        }
        return nearTeeth ? boneErrorMm : std::max(boneErrorMm, boneFarErrorMm);
    }
    /// The longest edge a triangle of interface (a, b) may have.
    double maxEdgeMm(Label a, Label b) const {
        switch (kindOf(a, b)) {
            case Kind::Cap: return capMaxEdgeMm;
            case Kind::Pdl: return pdlMaxEdgeMm;
            case Kind::Tooth: return toothMaxEdgeMm;
            case Kind::Bone: break;
        }
        return boneMaxEdgeMm;
    }

private:
    enum class Kind { Cap, Pdl, Tooth, Bone };
    static Kind kindOf(Label a, Label b) {
        const auto kind = [](Label l) { return l == kOutsideLabel ? LabelKind::Outside : labelKind(l); };
        const LabelKind ka = kind(a), kb = kind(b);
        const auto has = [&](LabelKind k) { return ka == k || kb == k; };
        if (has(LabelKind::Pdl) && has(LabelKind::Outside)) return Kind::Cap;
        if (has(LabelKind::Pdl)) return Kind::Pdl;
        if (has(LabelKind::Tooth) || has(LabelKind::Implant)) return Kind::Tooth;
        return Kind::Bone;
    }
};

}  // namespace jawmesh
