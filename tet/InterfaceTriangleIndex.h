// The interface triangles of a complex by their node triple, to find which tet faces are input
// triangles (labelling the tets from the triangles' sides, the hole cut). A sorted array searched
// by bisection: a std::map's millions of lookups, one per tet face of the mesh, were most of a
// second of the tet stage on the shared mandible.
#pragma once

#include "io/InterfaceComplex.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace jawmesh {

struct InterfaceTriangleIndex {
    using Key = std::array<std::int32_t, 3>;  ///< node indices, ascending
    static constexpr std::size_t npos = static_cast<std::size_t>(-1);
    std::vector<std::pair<Key, std::size_t>> sorted;  ///< (key, triangle), ascending

    /// The triangle with these nodes (the lowest index when repeated), or npos. O(log n).
    std::size_t find(const Key& key) const;
    bool contains(const Key& key) const { return find(key) != npos; }
};

/// Every triangle of `complex.surface` by its node triple. O(n log n).
InterfaceTriangleIndex interfaceTriangleIndex(const InterfaceComplex& complex);

}  // namespace jawmesh
