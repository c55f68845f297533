// Implements filters/RegionWedges.h; what it computes, its rules and its contract are documented there.
#include "filters/RegionWedges.h"

#include "io/Angles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace jawmesh {

double smallestRegionWedgeDeg(const Vec3& a, const Vec3& b, const EdgeFanTriangle* fan, std::size_t n, FanKind kind) {
    if (n < 2) return 360;
    const Vec3 d = (b - a).normalized();
    // Angles of the apexes around the edge, in a frame perpendicular to it.
    Vec3 x = Vec3::Zero();
    struct Spoke {
        double phi;
        Label lead, trail;  ///< region on the side of increasing / decreasing angle
    };
    std::array<Spoke, 16> local;
    std::vector<Spoke> heap;
    Spoke* spokes = local.data();
    if (n > local.size()) {
        heap.resize(n);
        spokes = heap.data();
    }
    for (std::size_t i = 0; i < n; ++i) {
        Vec3 r = fan[i].apex - a;
        r -= r.dot(d) * d;
        if (i == 0) x = r.normalized();
        const Vec3 y = d.cross(x);
        double phi = std::atan2(r.dot(y), r.dot(x));
        if (phi < 0) phi += 2 * kPi;
        // A triangle ordered a -> b has its normal along d x r: the side of increasing angle.
        const Label lead = fan[i].aThenB ? fan[i].front : fan[i].back;
        const Label trail = fan[i].aThenB ? fan[i].back : fan[i].front;
        spokes[i] = Spoke{phi, lead, trail};
    }
    std::sort(spokes, spokes + n, [](const Spoke& p, const Spoke& q) { return p.phi < q.phi; });
    double smallest = 360;
    for (std::size_t i = 0; i < n; ++i) {
        const Spoke& s = spokes[i];
        const Spoke& next = spokes[(i + 1) % n];
        if (s.lead != next.trail && kind == FanKind::Whole) return 0;
        if (s.lead != next.trail || s.lead == kOutsideLabel) continue;
        double gap = next.phi - s.phi;
        if (i + 1 == n) gap += 2 * kPi;
        smallest = std::min(smallest, gap * 180.0 / kPi);
    }
    return smallest;
}

RegionWedgeStats measureRegionWedges(const InterfaceComplex& complex, double thresholdDeg) {
    const auto& V = complex.surface.vertices;
    const auto& F = complex.surface.triangles;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> edges;
    edges.reserve(F.size() * 2);
    for (std::size_t t = 0; t < F.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const std::uint64_t p = std::uint32_t(F[t][k]), q = std::uint32_t(F[t][(k + 1) % 3]);
            edges[std::min(p, q) << 32 | std::max(p, q)].push_back(std::uint32_t(t));
        }
    RegionWedgeStats stats;
    std::vector<EdgeFanTriangle> fan;
    for (const auto& [key, tris] : edges) {
        const auto a = std::uint32_t(key >> 32), b = std::uint32_t(key & 0xffffffffu);
        fan.clear();
        for (std::uint32_t t : tris)
            fan.push_back(edgeFanTriangle(F[t], std::int32_t(a), std::int32_t(b), V[std::size_t(apexOf(F[t], std::int32_t(a), std::int32_t(b)))],
                                          complex.sides[t]));
        const double w = smallestRegionWedgeDeg(V[a], V[b], fan.data(), fan.size(), FanKind::Whole);
        stats.smallestDeg = std::min(stats.smallestDeg, w);
        if (w < thresholdDeg) {
            ++stats.edgesBelow;
            stats.below.push_back({0.5 * (V[a] + V[b]), w});
        }
    }
    std::sort(stats.below.begin(), stats.below.end(), [](const auto& x, const auto& y) {
        return std::lexicographical_compare(x.first.data(), x.first.data() + 3, y.first.data(), y.first.data() + 3);
    });
    return stats;
}

}  // namespace jawmesh
