// The triangles around each vertex of a triangle list, in compressed rows: one allocation for all
// of them, triangles in increasing index around every vertex.
#pragma once

#include "io/SurfaceMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace jawmesh {

struct VertexTriangles {
    std::vector<std::uint32_t> start;  ///< per vertex v: its triangles are list[start[v], start[v + 1])
    std::vector<std::int32_t> list;

    const std::int32_t* begin(std::int32_t v) const { return list.data() + start[std::size_t(v)]; }
    const std::int32_t* end(std::int32_t v) const { return list.data() + start[std::size_t(v) + 1]; }
    std::size_t count(std::int32_t v) const { return start[std::size_t(v) + 1] - start[std::size_t(v)]; }
};

/// The rows of `triangles` (indices below vertexCount, not checked). Cost O(vertices + triangles).
VertexTriangles vertexTriangles(const std::vector<Tri>& triangles, std::size_t vertexCount);

}  // namespace jawmesh
