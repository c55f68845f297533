// The holes of an interface complex as closed vertex loops: the open region edges
// (filters/OpenRegionEdges.h) chained per label pair and oriented as the boundary of the patch
// that would close them. Input of filters/FillSurfaceHoles.h.
#pragma once

#include "io/InterfaceComplex.h"

#include <array>
#include <vector>

namespace jawmesh {

struct HoleLoop {
    /// The two regions the missing patch separates, lower label first.
    std::array<Label, 2> pair{};
    /// Vertex indices in order, no vertex twice; the patch's boundary runs v[0] -> v[1] -> ... ->
    /// v[0] when its triangles are wound with their normal into pair[1] (out of pair[0]).
    std::vector<std::int32_t> vertices;
};

struct HoleLoops {
    std::vector<HoleLoop> loops;
    /// Open edges that belong to no loop: more than two labels open at the edge, or a chain that
    /// does not close (the complex is broken beyond a missing patch there).
    std::size_t strayEdges = 0;
};

/// Chains the open edges of `complex` into loops. An edge whose open labels are exactly {A, B}
/// is a boundary edge of a hole in the A/B sheet; its direction is the one that cancels what the
/// triangles around it give region A's outward-oriented boundary (a closed boundary cancels on
/// every edge). Loops that touch at a vertex (two holes sharing a corner) are split there, so no
/// loop repeats a vertex. Deterministic. Cost: O(T log T) for T triangles.
HoleLoops holeLoops(const InterfaceComplex& complex);

}  // namespace jawmesh
