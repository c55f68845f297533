// Implements tet/HolePoints.h; what it computes, its rules and its contract are documented there.
#include "tet/HolePoints.h"

#include "filters/TriangleGeometry.h"

#include <cmath>

namespace jawmesh {
namespace {

/// Whether p lies at least `clearance` mm from every triangle of `near`.
bool clearOf(const SurfaceMesh& s, const std::vector<std::size_t>& near, const Vec3& p, double clearance) {
    for (const std::size_t t : near) {
        const Tri& f = s.triangles[t];
        const double d2 = squaredDistanceToTriangle(p, s.vertices[std::size_t(f[0])], s.vertices[std::size_t(f[1])],
                                                    s.vertices[std::size_t(f[2])]);
        if (d2 < clearance * clearance) return false;
    }
    return true;
}

void addLatticeInHole(const SurfaceMesh& s, const FilledHole& hole, std::vector<Vec3>& points) {
    if (hole.boundaryEdges == 0 || !(hole.diameterMm > 0)) return;
    const double spacing = kHolePointSpacing * M_PI * hole.diameterMm / double(hole.boundaryEdges);
    const double radius = 0.5 * hole.diameterMm + 2.0 * spacing;
    BBox box;
    box.extend(hole.centre - Vec3::Constant(radius + spacing));
    box.extend(hole.centre + Vec3::Constant(radius + spacing));
    std::vector<std::size_t> near;
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
        if (box.overlaps(triangleBox(s, s.triangles[t]))) near.push_back(t);
    const int steps = int(std::ceil(radius / spacing));
    for (int i = -steps; i <= steps; ++i)
        for (int j = -steps; j <= steps; ++j)
            for (int k = -steps; k <= steps; ++k) {
                const Vec3 p = hole.centre + spacing * Vec3(i, j, k);
                if ((p - hole.centre).norm() <= radius && clearOf(s, near, p, 0.5 * spacing)) points.push_back(p);
            }
}

}  // namespace

std::vector<Vec3> pointsInHoles(const SurfaceMesh& surface, const std::vector<FilledHole>& holes) {
    std::vector<Vec3> points;
    for (const FilledHole& hole : holes) addLatticeInHole(surface, hole, points);
    return points;
}

}  // namespace jawmesh
