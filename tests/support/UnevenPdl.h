// Segmented PDLs of uneven thickness, as issue #23's held-out label volume has them: for label
// volumes made from surfaces (levelset/SurfacesToLabelVolume.h) by the tests and bench_label_map.
#pragma once

#include "levelset/SurfacesToLabelVolume.h"

#include <cmath>

namespace jawmesh::test {

/// PDL labels whose thickness varies smoothly between minMm and maxMm around and along every root
/// (a product of two plane waves about 3-7 mm long, shifted per tooth), so a 0.1 mm volume holds
/// PDLs from one to several voxels thick.
inline SegmentedPdlLabels unevenPdlLabels(double minMm, double maxMm) {
    SegmentedPdlLabels pdl;
    pdl.maxThicknessMm = maxMm;
    pdl.thicknessMm = [minMm, maxMm](const Vec3& p, int unn) {
        const double wave = std::sin(1.3 * p.x() + 0.7 * p.y() + 1.1 * p.z() + unn) *
                            std::sin(0.9 * p.z() - 0.6 * p.x() + 0.5 * unn);
        return minMm + (maxMm - minMm) * 0.5 * (1 + wave);
    };
    return pdl;
}

}  // namespace jawmesh::test
