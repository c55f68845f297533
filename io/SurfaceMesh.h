// Plain triangle-surface data shared by every stage: vertices in millimetres, triangles as
// vertex-index triples. A SurfaceMesh may be a "triangle soup": no closedness, manifoldness or
// orientation is assumed by the type; stages that need those check them.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace jawmesh {

using Vec3 = Eigen::Vector3d;
using Tri = std::array<std::int32_t, 3>;

struct SurfaceMesh {
    std::vector<Vec3> vertices;   ///< positions, mm
    std::vector<Tri> triangles;   ///< indices into vertices
};

/// Key of the undirected edge a-b (non-negative vertex indices): (min << 32) | max.
inline std::uint64_t edgeKey(std::int32_t a, std::int32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

/// Axis-aligned bounding box, mm. Empty when min > max.
struct BBox {
    Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());
    bool empty() const { return (min.array() > max.array()).any(); }
    void extend(const Vec3& p) { min = min.cwiseMin(p); max = max.cwiseMax(p); }
    void extend(const BBox& b) { if (!b.empty()) { extend(b.min); extend(b.max); } }
    Vec3 size() const { return empty() ? Vec3::Zero() : Vec3(max - min); }
    /// True when the two boxes share a point (closed boxes).
    bool overlaps(const BBox& b) const { return (min.array() <= b.max.array()).all() && (b.min.array() <= max.array()).all(); }
    /// Squared distance from p to the closed box (0 inside), mm^2.
    double squaredDistance(const Vec3& p) const { return (min - p).cwiseMax(p - max).cwiseMax(0.0).squaredNorm(); }
};

/// Bounding box of the vertices referenced by at least one triangle (unused vertices ignored).
BBox boundingBox(const SurfaceMesh& mesh);

/// Bounding box of triangle t of mesh.
inline BBox triangleBox(const SurfaceMesh& mesh, const Tri& t) {
    BBox b;
    for (const std::int32_t v : t) b.extend(mesh.vertices[std::size_t(v)]);
    return b;
}

/// Signed volume (mm^3) enclosed by the triangles, by the divergence theorem; positive for a
/// closed, outward-oriented surface. Meaningless for open or inconsistently oriented meshes.
double signedVolume(const SurfaceMesh& mesh);

/// The triangles `triangles` (indices into `vertices`) over only the vertices they use, kept in
/// index order. Cost: O(k log k) for k triangle corners (no array as large as `vertices`).
SurfaceMesh compactSurface(const std::vector<Vec3>& vertices, std::vector<Tri> triangles);

/// Appends b to a (indices of b shifted).
void append(SurfaceMesh& a, const SurfaceMesh& b);

}  // namespace jawmesh
