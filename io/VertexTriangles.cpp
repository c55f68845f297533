// Implements io/VertexTriangles.h; what it computes, its rules and its contract are documented there.
#include "io/VertexTriangles.h"

namespace jawmesh {

VertexTriangles vertexTriangles(const std::vector<Tri>& triangles, std::size_t vertexCount) {
    VertexTriangles r;
    r.start.assign(vertexCount + 1, 0);
    for (const Tri& f : triangles)
        for (std::int32_t v : f) ++r.start[std::size_t(v) + 1];
    for (std::size_t v = 1; v < r.start.size(); ++v) r.start[v] += r.start[v - 1];
    r.list.resize(r.start.back());
    std::vector<std::uint32_t> next(r.start.begin(), r.start.end() - 1);
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (std::int32_t v : triangles[t]) r.list[next[std::size_t(v)]++] = std::int32_t(t);
    return r;
}

}  // namespace jawmesh
