// Implements levelset/UnionBoundary.h; what it computes, its rules and its contract are documented there.
#include "levelset/UnionBoundary.h"

#include "levelset/OrientSurface.h"

#include <tbb/parallel_for.h>

#include <vector>

namespace jawmesh {

bool bothSidesAlike(const LineWindingQuery& query, const Vec3& a, const Vec3& b, const Vec3& c, double offsetMm, int firstLine) {
    const Vec3 n = (b - a).cross(c - a).normalized() * offsetMm;
    const Vec3 m = (a + b + c) / 3.0;
    int same = 0, differ = 0;
    for (int k = 0; k < 5 && same < 2 && differ < 2; ++k) {
        const Vec3 d = LineWindingQuery::genericDirection(firstLine + k);
        const auto front = query.windingAlongLine(m + n, d);
        const auto back = query.windingAlongLine(m - n, d);
        if (!front || !back) continue;
        ((*front >= 1) == (*back >= 1) ? same : differ) += 1;
    }
    return same >= 2;
}

SurfaceMesh unionBoundary(const SurfaceMesh& mesh) {
    const OrientedSurface oriented = orientSurface(mesh);
    if (oriented.patchCount <= 1) return mesh;
    const LineWindingQuery query(oriented.vertices, oriented.triangles, {});
    // A hundredth of the bounding box's smallest side: off the face, inside the thinnest shell.
    const double offsetMm = 1e-4 * boundingBox(mesh).size().minCoeff();
    std::vector<char> inner(oriented.triangles.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, oriented.triangles.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t < r.end(); ++t) {
            const Tri& tri = oriented.triangles[t];
            const auto corner = [&](int k) { return oriented.vertices[static_cast<std::size_t>(tri[static_cast<std::size_t>(k)])]; };
            inner[t] = bothSidesAlike(query, corner(0), corner(1), corner(2), offsetMm, static_cast<int>(t % 64));
        }
    });
    SurfaceMesh out;
    out.vertices = oriented.vertices;
    for (std::size_t t = 0; t < oriented.triangles.size(); ++t)
        if (!inner[t]) out.triangles.push_back(oriented.triangles[t]);
    return out;
}

JawSurfaces toothUnionBoundaries(JawSurfaces surfaces) {
    for (auto& [unn, mesh] : surfaces.teeth) mesh = unionBoundary(mesh);
    return surfaces;
}

}  // namespace jawmesh
