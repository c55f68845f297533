// Small holes of an oriented surface closed by patches before the distance band is computed, so
// that the band runs across them. Without a patch the winding numbers still close a hole, but
// there is no triangle there: the sign then jumps between ±background with no distance band
// (OpenVDB's flood fill places the jump), and carving, which reads the bone's distance and its
// direction, makes no PDL there (issue #27, docs/DESIGN.md "Known pitfalls").
#pragma once

#include "levelset/OrientSurface.h"

#include <cstddef>

namespace jawmesh {

/// Loops of more vertices than this are left open (the winding numbers still close them): the
/// least-area patch costs O(n^3), and a loop that long is a cut, not a hole.
constexpr std::size_t kMaxHoleLoopVertices = 400;

struct ClosedHoles {
    std::size_t loops = 0;      ///< holes closed
    std::size_t triangles = 0;  ///< patch triangles added
    std::size_t leftOpen = 0;   ///< loops over kMaxHoleLoopVertices, and open chains that do not close
};

/// Closes every hole of `surface` (a loop of edges used by one triangle each) of at most
/// maxLoopVertices vertices with the triangulation of least area over its own vertices (no vertex
/// added), wound to continue the orientation of the triangles around it; each patch takes the
/// patch id of the triangle along its first edge. Loops touching at a vertex are closed
/// separately. Edges used by two or more triangles are never hole edges, so a closed surface comes
/// back unchanged. Zero-area patch triangles are left out. Deterministic.
/// Cost: O(T log T) for T triangles, plus O(n^3) per loop of n vertices.
ClosedHoles closeSmallHoles(OrientedSurface& surface, std::size_t maxLoopVertices = kMaxHoleLoopVertices);

}  // namespace jawmesh
