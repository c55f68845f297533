// Implements filters/PatchWedge.h; what it computes, its rules and its contract are documented there.
#include "filters/PatchWedge.h"

#include "filters/PatchChecks.h"
#include "filters/RegionWedges.h"

#include <algorithm>
#include <map>

namespace jawmesh {

double patchSmallestWedgeDeg(const InterfaceComplex& c, const std::vector<std::int32_t>& near, const std::vector<Tri>& patch,
                             const std::vector<Vec3>& added, const std::array<Label, 2>& sides) {
    const auto at = [&](std::int32_t v) -> const Vec3& { return patchPoint(c.surface, added, v); };
    // Per edge of the patch (lower index first): its triangles as (corners, sides).
    struct Entry {
        Tri tri;
        std::array<Label, 2> sides;
    };
    std::map<std::pair<std::int32_t, std::int32_t>, std::vector<Entry>> fans;
    const auto key = [](std::int32_t a, std::int32_t b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
    for (const Tri& t : patch)
        for (std::size_t k = 0; k < 3; ++k) fans[key(t[k], t[(k + 1) % 3])].push_back({t, sides});
    for (const std::int32_t n : near) {
        const Tri& t = c.surface.triangles[std::size_t(n)];
        for (std::size_t k = 0; k < 3; ++k) {
            const auto it = fans.find(key(t[k], t[(k + 1) % 3]));
            if (it != fans.end()) it->second.push_back({t, c.sides[std::size_t(n)]});
        }
    }
    double smallest = 360;
    std::vector<EdgeFanTriangle> fan;
    for (const auto& [edge, entries] : fans) {
        const auto [a, b] = edge;
        fan.clear();
        for (const Entry& e : entries) fan.push_back(edgeFanTriangle(e.tri, a, b, at(apexOf(e.tri, a, b)), e.sides));
        smallest = std::min(smallest, smallestRegionWedgeDeg(at(a), at(b), fan.data(), fan.size(), FanKind::Whole));
    }
    return smallest;
}

}  // namespace jawmesh
