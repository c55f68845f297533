// The surface-nets quads of a label field: one per label edge (filters/LabelEdges.h), joining the
// vertices of the four dual cells around it, and their triangles. Shared by the fine extraction, the
// adaptive one (filters/AdaptiveCells.h: several dual cells may share one vertex) and its error
// certificate (the fine triangles around a cell), so all three cut every quad the same way.
#pragma once

#include "filters/LabelEdges.h"
#include "io/SurfaceMesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace jawmesh {

struct DualQuad {
    std::array<std::int32_t, 4> cells;  ///< dual cell indices in order around the edge
    std::array<Label, 2> sides;         ///< smaller label first; the quad's normal points into it
};

/// The quads of all label edges (cells from dualCellsOf(edges)); `mirrored` when the grid's
/// index-to-world map has a negative determinant. Parallel, deterministic.
std::vector<DualQuad> dualQuadsOf(const std::vector<LabelEdge>& edges, const std::vector<openvdb::Coord>& cells,
                                  const openvdb::Int32Grid& labels, bool mirrored);

/// The triangles of a quad whose corners are the vertices q (positions P): two, split along the
/// shorter diagonal; one when two neighbouring corners are the same vertex; none when fewer than
/// three corners differ. Returns how many were written to out.
int quadTriangles(std::array<std::int32_t, 4> q, const std::vector<Vec3>& P, Tri out[2]);

/// All triangles of `quads` with corner cell c replaced by vertex vertexOf[c] (positions P), in
/// quad order, with their label pairs. Parallel, deterministic.
void emitQuadTriangles(const std::vector<DualQuad>& quads, const std::vector<std::int32_t>& vertexOf,
                       const std::vector<Vec3>& P, std::vector<Tri>& triangles,
                       std::vector<std::array<Label, 2>>& sides);

}  // namespace jawmesh
