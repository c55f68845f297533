// The error bound of each interface (label pair) against the fine interface, mm: what the adaptive
// extraction (AdaptiveCells.h) and the simplification (SimplifyInterfaces.h) may spend. One place, so
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

    /// The bound of interface (a, b); nearTeeth only matters on bone / outside.
    double boundMm(Label a, Label b, bool nearTeeth) const {
        const auto kind = [](Label l) { return l == kOutsideLabel ? LabelKind::Outside : labelKind(l); };
        const LabelKind ka = kind(a), kb = kind(b);
        const auto has = [&](LabelKind k) { return ka == k || kb == k; };
        if (has(LabelKind::Pdl) && has(LabelKind::Outside)) return toothErrorMm;
        if (has(LabelKind::Pdl)) return pdlErrorMm;
        if (has(LabelKind::Tooth)) return toothErrorMm;
        return nearTeeth ? boneErrorMm : std::max(boneErrorMm, boneFarErrorMm);
    }
};

}  // namespace jawmesh
