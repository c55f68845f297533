// Implements tet/HolePoints.h; what it computes, its rules and its contract are documented there.
#include "tet/HolePoints.h"

#include "filters/TriangleBoxGrid.h"
#include "filters/TriangleGeometry.h"

#include <algorithm>
#include <cmath>

namespace jawmesh {
namespace {

/// Whether p lies at least `clearance` mm from every triangle of s in `grid` (cells of at least
/// the clearance).
bool clearOf(const SurfaceMesh& s, TriangleBoxGrid& grid, const Vec3& p, double clearance) {
    BBox reach;
    reach.extend(p - Vec3::Constant(clearance));
    reach.extend(p + Vec3::Constant(clearance));
    bool clear = true;
    grid.query(reach, [&](std::int32_t t) {
        const Tri& f = s.triangles[std::size_t(t)];
        if (clear && squaredDistanceToTriangle(p, s.vertices[std::size_t(f[0])], s.vertices[std::size_t(f[1])],
                                               s.vertices[std::size_t(f[2])]) < clearance * clearance)
            clear = false;
    });
    return clear;
}

void addLatticeInHole(const SurfaceMesh& s, const FilledHole& hole, std::vector<Vec3>& points) {
    if (hole.boundaryEdges == 0 || !(hole.diameterMm > 0)) return;
    const double spacing = std::max(kHolePointSpacing * M_PI * hole.diameterMm / double(hole.boundaryEdges),
                                    hole.diameterMm / kMaxHoleLatticeSpans);
    const double radius = 0.5 * hole.diameterMm + 2.0 * spacing;
    BBox box;
    box.extend(hole.centre - Vec3::Constant(radius + spacing));
    box.extend(hole.centre + Vec3::Constant(radius + spacing));
    TriangleBoxGrid grid(spacing);
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        const BBox b = triangleBox(s, s.triangles[t]);
        if (box.overlaps(b)) grid.place(std::int32_t(t), b);
    }
    const int steps = int(std::ceil(radius / spacing));
    for (int i = -steps; i <= steps; ++i)
        for (int j = -steps; j <= steps; ++j)
            for (int k = -steps; k <= steps; ++k) {
                const Vec3 p = hole.centre + spacing * Vec3(i, j, k);
                if ((p - hole.centre).norm() <= radius && clearOf(s, grid, p, 0.5 * spacing)) points.push_back(p);
            }
}

}  // namespace

std::vector<Vec3> pointsInHoles(const SurfaceMesh& surface, const std::vector<FilledHole>& holes) {
    std::vector<Vec3> points;
    for (const FilledHole& hole : holes) {
        const std::size_t before = points.size();
        addLatticeInHole(surface, hole, points);
        if (points.size() > kMaxHolePoints) {
            points.resize(before);  // this hole's lattice would pass the cap: it and the rest get none
            break;
        }
    }
    return points;
}

}  // namespace jawmesh
