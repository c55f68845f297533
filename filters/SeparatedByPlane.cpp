// The floating-point filter before the exact triangle-pair test (SeparatedByPlane.h).
#include "filters/SeparatedByPlane.h"

#include <cmath>

namespace jawmesh {

bool separatedByPlane(const Vec3 a[3], const Tri& ia, const Vec3 b[3], const Tri& ib) {
    // Two triangles on one edge meet only when folded onto each other: apexes clearly on opposite
    // sides of the edge (seen across it) rules that out, coplanar or not.
    int sa[3], sb[3], shared = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (ia[i] == ib[j]) {
                sa[shared] = i;
                sb[shared] = j;
                ++shared;
            }
    if (shared == 2) {
        const Vec3& s = a[sa[0]];
        const Vec3 e = (a[sa[1]] - s).normalized();
        Vec3 da = a[3 - sa[0] - sa[1]] - s, db = b[3 - sb[0] - sb[1]] - s;
        da -= e * e.dot(da);
        db -= e * e.dot(db);
        return da.dot(db) < -1e-9 * da.norm() * db.norm();
    }
    const Vec3 n = (a[1] - a[0]).cross(a[2] - a[0]);
    const double scale = (a[1] - a[0]).squaredNorm() + (a[2] - a[0]).squaredNorm() + (b[0] - a[0]).squaredNorm() +
                         (b[1] - a[0]).squaredNorm() + (b[2] - a[0]).squaredNorm();
    const double margin = 1e-12 * scale * std::sqrt(scale);
    int above = 0, below = 0, free = 0;
    for (int k = 0; k < 3; ++k) {
        if (ib[k] == ia[0] || ib[k] == ia[1] || ib[k] == ia[2]) continue;
        ++free;
        const double d = n.dot(b[k] - a[0]);
        if (d > margin) ++above;
        else if (d < -margin) ++below;
    }
    return free > 0 && (above == free || below == free);
}

}  // namespace jawmesh
