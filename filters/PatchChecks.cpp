// Implements filters/PatchChecks.h; what it computes, its rules and its contract are documented there.
#include "filters/PatchChecks.h"

#include "filters/SelfIntersections.h"

#include <algorithm>
#include <cmath>

namespace jawmesh {
namespace {

/// Solid angle, steradians, that triangle a b c subtends at p (Van Oosterom and Strackee), signed by
/// its winding.
double solidAngle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 x = a - p, y = b - p, z = c - p;
    const double lx = x.norm(), ly = y.norm(), lz = z.norm();
    return 2.0 * std::atan2(x.dot(y.cross(z)), lx * ly * lz + x.dot(y) * lz + x.dot(z) * ly + y.dot(z) * lx);
}

}  // namespace

bool patchIsClean(const SurfaceMesh& s, const std::vector<Tri>& patch, const std::vector<Vec3>& added,
                  const std::vector<std::int32_t>& near) {
    const auto corners = [&](const Tri& t, Vec3 out[3]) {
        for (std::size_t k = 0; k < 3; ++k) out[k] = patchPoint(s, added, t[k]);
    };
    for (std::size_t i = 0; i < patch.size(); ++i) {
        Vec3 a[3];
        corners(patch[i], a);
        if (triangleDegenerate(a[0], a[1], a[2])) return false;
        BBox box;
        for (const Vec3& x : a) box.extend(x);
        for (std::size_t j = i + 1; j < patch.size(); ++j) {
            Vec3 b[3];
            corners(patch[j], b);
            if (trianglesIntersect(a, patch[i], b, patch[j])) return false;
        }
        for (const std::int32_t t : near) {
            const Tri& other = s.triangles[std::size_t(t)];
            if (!box.overlaps(triangleBox(s, other))) continue;
            Vec3 b[3];
            corners(other, b);
            if (trianglesIntersect(a, patch[i], b, other)) return false;
        }
    }
    return true;
}

bool patchSweepsAVertex(const SurfaceMesh& s, const std::vector<std::int32_t>& near, const std::vector<std::int32_t>& rim,
                        const std::vector<Tri>& from, const std::vector<Vec3>& fromAdded, const std::vector<Tri>& to,
                        const std::vector<Vec3>& toAdded, const std::vector<RegionSeed>& seeds) {
    const auto between = [&](const Vec3& p) {
        double omega = 0;
        for (const Tri& f : from) omega += solidAngle(p, patchPoint(s, fromAdded, f[0]), patchPoint(s, fromAdded, f[1]), patchPoint(s, fromAdded, f[2]));
        for (const Tri& f : to) omega -= solidAngle(p, patchPoint(s, toAdded, f[0]), patchPoint(s, toAdded, f[1]), patchPoint(s, toAdded, f[2]));
        return std::abs(omega) > 2.0 * M_PI;  // |winding number| > 1/2
    };
    std::vector<std::int32_t> tested(rim.begin(), rim.end());
    std::sort(tested.begin(), tested.end());
    for (const std::int32_t t : near)
        for (const std::int32_t v : s.triangles[std::size_t(t)]) {
            const auto it = std::lower_bound(tested.begin(), tested.end(), v);
            if (it != tested.end() && *it == v) continue;
            tested.insert(it, v);
            if (between(s.vertices[std::size_t(v)])) return true;
        }
    return std::any_of(seeds.begin(), seeds.end(), [&](const RegionSeed& seed) { return between(seed.point); });
}

}  // namespace jawmesh
