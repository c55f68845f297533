// Implements fe/ExteriorFaces.h; what it computes, its rules and its contract are documented there.
#include "fe/ExteriorFaces.h"

#include "tet/TetFaceAdjacency.h"

namespace jawmesh {

std::vector<ExteriorFace> exteriorFaces(const TetMesh& mesh) {
    const TetFaceAdjacency adjacency = tetFaceAdjacency(mesh);
    std::vector<ExteriorFace> faces;
    for (std::size_t g = 0; g < adjacency.groupCount(); ++g) {
        if (adjacency.groupSize(g) != 1) continue;
        const TetFaceRef& f = adjacency.faces[static_cast<std::size_t>(adjacency.groupStart[g])];
        const auto tet = static_cast<std::size_t>(f.tet);
        faces.push_back({outwardFace(mesh.tets[tet], f.local), mesh.labels[tet], f.tet, f.local});
    }
    return faces;
}

double triangleArea(const std::vector<Vec3>& nodes, const Tri& t) {
    const Vec3& a = nodes[static_cast<std::size_t>(t[0])];
    return 0.5 * (nodes[static_cast<std::size_t>(t[1])] - a).cross(nodes[static_cast<std::size_t>(t[2])] - a).norm();
}

Vec3 triangleNormal(const std::vector<Vec3>& nodes, const Tri& t) {
    const Vec3& a = nodes[static_cast<std::size_t>(t[0])];
    const Vec3 n = (nodes[static_cast<std::size_t>(t[1])] - a).cross(nodes[static_cast<std::size_t>(t[2])] - a);
    const double length = n.norm();
    return length > 0 ? Vec3(n / length) : Vec3::Zero();
}

}  // namespace jawmesh
