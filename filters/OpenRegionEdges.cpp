// Implements filters/OpenRegionEdges.h; what it computes, its rules and its contract are documented there.
#include "filters/OpenRegionEdges.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <tuple>

namespace jawmesh {

std::vector<OpenRegionEdge> openRegionEdges(const InterfaceComplex& complex) {
    std::vector<OpenRegionEdge> uses;
    uses.reserve(6 * complex.surface.triangles.size());
    for (std::size_t t = 0; t < complex.surface.triangles.size(); ++t) {
        const Tri& tri = complex.surface.triangles[t];
        for (int k = 0; k < 3; ++k) {
            const std::int32_t a = tri[std::size_t(k)], b = tri[std::size_t((k + 1) % 3)];
            for (const Label side : complex.sides[t]) uses.push_back({std::min(a, b), std::max(a, b), side});
        }
    }
    const auto key = [](const OpenRegionEdge& e) { return std::tie(e.a, e.b, e.label); };
    // equal keys are equal entries, so any sort gives the same list (6 per triangle: a parallel one)
    tbb::parallel_sort(uses.begin(), uses.end(), [&](const auto& x, const auto& y) { return key(x) < key(y); });
    std::vector<OpenRegionEdge> open;
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i;
        while (j < uses.size() && key(uses[j]) == key(uses[i])) ++j;
        if ((j - i) % 2 == 1) open.push_back(uses[i]);
        i = j;
    }
    return open;
}

}  // namespace jawmesh
