#include "io/SurfaceMesh.h"

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

void append(SurfaceMesh& a, const SurfaceMesh& b) {
    const auto offset = static_cast<std::int32_t>(a.vertices.size());
    a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
    a.triangles.reserve(a.triangles.size() + b.triangles.size());
    for (const Tri& t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

}  // namespace jawmesh
