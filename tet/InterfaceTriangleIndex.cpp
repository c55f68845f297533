// Implements tet/InterfaceTriangleIndex.h; what it computes, its rules and its contract are documented there.
#include "tet/InterfaceTriangleIndex.h"

#include <algorithm>

namespace jawmesh {

std::size_t InterfaceTriangleIndex::find(const Key& key) const {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), key,
                                     [](const std::pair<Key, std::size_t>& e, const Key& k) { return e.first < k; });
    return it != sorted.end() && it->first == key ? it->second : npos;
}

InterfaceTriangleIndex interfaceTriangleIndex(const InterfaceComplex& complex) {
    InterfaceTriangleIndex index;
    index.sorted.reserve(complex.surface.triangles.size());
    for (std::size_t t = 0; t < complex.surface.triangles.size(); ++t) {
        Tri key = complex.surface.triangles[t];
        std::sort(key.begin(), key.end());
        index.sorted.emplace_back(key, t);
    }
    std::sort(index.sorted.begin(), index.sorted.end());  // equal keys: the lowest triangle first
    return index;
}

}  // namespace jawmesh
