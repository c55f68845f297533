// Implements levelset/LevelSetSurface.h; what it computes, its rules and its contract are documented there.
#include "levelset/LevelSetSurface.h"

#include "io/Error.h"

#include <openvdb/tools/VolumeToMesh.h>

#include <utility>

namespace jawmesh {

SurfaceMesh extractLevelSetSurface(const openvdb::FloatGrid& grid, double isovalue) {
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(grid, points, tris, quads, isovalue, 0.0, true);
    if (quads.empty() && tris.empty()) throw Error("a level set holds no surface");
    SurfaceMesh mesh;
    mesh.vertices.reserve(points.size());
    for (const auto& p : points) mesh.vertices.emplace_back(p.x(), p.y(), p.z());
    mesh.triangles.reserve(tris.size() + 2 * quads.size());
    auto idx = [](openvdb::Index i) { return static_cast<std::int32_t>(i); };
    for (const auto& t : tris) mesh.triangles.push_back({idx(t[0]), idx(t[1]), idx(t[2])});
    for (const auto& q : quads) {
        const auto& v = mesh.vertices;
        if ((v[q[0]] - v[q[2]]).squaredNorm() <= (v[q[1]] - v[q[3]]).squaredNorm()) {
            mesh.triangles.push_back({idx(q[0]), idx(q[1]), idx(q[2])});
            mesh.triangles.push_back({idx(q[0]), idx(q[2]), idx(q[3])});
        } else {
            mesh.triangles.push_back({idx(q[0]), idx(q[1]), idx(q[3])});
            mesh.triangles.push_back({idx(q[1]), idx(q[2]), idx(q[3])});
        }
    }
    // volumeToMesh's winding follows its own convention; make the surface outward-facing.
    if (signedVolume(mesh) < 0)
        for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
    return mesh;
}

}  // namespace jawmesh
