// Implements io/SurfaceMesh.h; what it computes, its rules and its contract are documented there.
#include "io/SurfaceMesh.h"

#include <algorithm>

namespace jawmesh {

BBox boundingBox(const SurfaceMesh& mesh) {
    BBox box;
    for (const Tri& t : mesh.triangles)
        for (std::int32_t v : t) box.extend(mesh.vertices[static_cast<std::size_t>(v)]);
    return box;
}

double signedVolume(const SurfaceMesh& mesh) {
    double sixVolume = 0.0;
    for (const Tri& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        sixVolume += a.dot(b.cross(c));
    }
    return sixVolume / 6.0;
}

SurfaceMesh compactSurface(const std::vector<Vec3>& vertices, std::vector<Tri> triangles) {
    std::vector<std::int32_t> used;
    used.reserve(3 * triangles.size());
    for (const Tri& t : triangles) used.insert(used.end(), t.begin(), t.end());
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    SurfaceMesh s;
    s.vertices.reserve(used.size());
    for (std::int32_t v : used) s.vertices.push_back(vertices[static_cast<std::size_t>(v)]);
    for (Tri& t : triangles)
        for (auto& v : t) v = static_cast<std::int32_t>(std::lower_bound(used.begin(), used.end(), v) - used.begin());
    s.triangles = std::move(triangles);
    return s;
}

void append(SurfaceMesh& a, const SurfaceMesh& b) {
    const auto offset = static_cast<std::int32_t>(a.vertices.size());
    a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
    a.triangles.reserve(a.triangles.size() + b.triangles.size());
    for (const Tri& t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

}  // namespace jawmesh
