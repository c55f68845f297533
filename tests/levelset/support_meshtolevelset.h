// Shapes, corruptions and sign checks shared by the quick and slow tests of meshToLevelSet().
#pragma once

#include "io/SurfaceMesh.h"
#include "levelset/BandDistance.h"
#include "support/DirtySurfaces.h"
#include "support/Icosphere.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <utility>

namespace jawmesh::test {

/// Outward axis-aligned box, 12 triangles.
inline SurfaceMesh boxMesh(const Vec3& lo, const Vec3& hi) {
    SurfaceMesh m;
    for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
    m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return m;
}

/// Distance from p to triangle abc (any units), by the closest-point regions of the triangle
/// (Ericson, Real-Time Collision Detection 5.1.5); degenerate triangles give their nearest edge.
inline double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    auto segment = [&](const Vec3& u, const Vec3& v) {
        const Vec3 e = v - u;
        const double len2 = e.squaredNorm();
        const double t = len2 > 0 ? std::clamp((p - u).dot(e) / len2, 0.0, 1.0) : 0.0;
        return (p - (u + t * e)).norm();
    };
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const Vec3 n = ab.cross(ac);
    if (n.squaredNorm() <= 1e-24 * ab.squaredNorm() * ac.squaredNorm()) return std::min({segment(a, b), segment(b, c), segment(c, a)});
    // Inside the prism over the triangle: plane distance; otherwise the nearest edge.
    const bool over = n.dot(ab.cross(ap)) >= 0 && n.dot((c - b).cross(p - b)) >= 0 && n.dot((a - c).cross(p - c)) >= 0;
    if (over) return std::abs(n.normalized().dot(ap));
    return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

/// Distance from p to the nearest triangle, by brute force.
inline double distanceToTriangles(const std::vector<Vec3>& vertices, const std::vector<Tri>& triangles, const Vec3& p) {
    double best = std::numeric_limits<double>::infinity();
    for (const Tri& t : triangles)
        best = std::min(best, pointTriangleDistance(p, vertices[static_cast<std::size_t>(t[0])], vertices[static_cast<std::size_t>(t[1])],
                                                    vertices[static_cast<std::size_t>(t[2])]));
    return best;
}

struct SignCheck {
    std::size_t checked = 0;
    std::size_t agreed = 0;
    double fraction() const { return checked ? static_cast<double>(agreed) / static_cast<double>(checked) : 0.0; }
};

/// Sign check on the clean, closed, outward surface `clean`: samples at triangle centroids (every
/// `stride`-th triangle), offset by +-offsetVoxels along the face normal, must read + outside and
/// - inside from the trilinearly interpolated grid. A sample is skipped when its offset point lies
/// within 1.0 voxel of another part of the clean surface (exact unsigned distance of the clean
/// mesh), where the truth is ambiguous. Built once per clean mesh, reused for its copies.
class OffsetSampleChecker {
public:
    OffsetSampleChecker(const SurfaceMesh& clean, double voxelMm, double offsetVoxels = 1.5, std::size_t stride = 1) {
        const double h = voxelMm;
        // The exact band distance (levelset/BandDistance.h): OpenVDB's meshToVolume took 25 s of
        // the bone's 30 s set-up, once per test process.
        std::vector<Vec3> indexVertices;
        for (const auto& v : clean.vertices) indexVertices.push_back(v / h);
        const auto unsignedClean = openvdb::FloatGrid::create(bandDistance(indexVertices, clean.triangles, h, offsetVoxels + 1.5));
        unsignedClean->setTransform(openvdb::math::Transform::createLinearTransform(h));
        const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> distance(*unsignedClean);
        for (std::size_t i = 0; i < clean.triangles.size(); i += stride) {
            const Tri& t = clean.triangles[i];
            const Vec3& a = clean.vertices[static_cast<std::size_t>(t[0])];
            const Vec3& b = clean.vertices[static_cast<std::size_t>(t[1])];
            const Vec3& c = clean.vertices[static_cast<std::size_t>(t[2])];
            const Vec3 n = (b - a).cross(c - a);
            if (n.norm() == 0.0) continue;
            const Vec3 centre = (a + b + c) / 3.0;
            for (int side : {-1, 1}) {
                const Vec3 q = centre + side * offsetVoxels * h * n.normalized();
                const openvdb::Vec3d wq(q.x(), q.y(), q.z());
                if (distance.wsSample(wq) < 1.0 * h) continue;
                samples_.push_back({wq, side < 0});
            }
        }
    }

    std::size_t sampleCount() const { return samples_.size(); }

    SignCheck check(const openvdb::FloatGrid& grid) const {
        const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sample(grid);
        SignCheck result;
        for (const auto& s : samples_) {
            ++result.checked;
            const float value = sample.wsSample(s.point);
            if (s.inside ? value < 0.0f : value > 0.0f) ++result.agreed;
        }
        return result;
    }

private:
    struct Sample {
        openvdb::Vec3d point;
        bool inside;
    };
    std::vector<Sample> samples_;
};

/// Fraction of active voxels whose sign matches the analytic signed distance `sdf` (mm), over
/// voxels with |sdf| >= minAbsVoxels voxels (closer ones are decided by faceting, not by sign).
inline SignCheck checkActiveVoxels(const openvdb::FloatGrid& grid, const std::function<double(const Vec3&)>& sdf,
                                   double minAbsVoxels = 0.5) {
    const double h = grid.voxelSize()[0];
    SignCheck check;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        const openvdb::Vec3d w = grid.indexToWorld(it.getCoord());
        const double s = sdf(Vec3(w.x(), w.y(), w.z()));
        if (std::abs(s) < minAbsVoxels * h) continue;
        ++check.checked;
        if ((s < 0) == (*it < 0.0f)) ++check.agreed;
    }
    return check;
}

/// Face-neighbour voxel pairs (a voxel of a leaf node and its +x, +y or +z neighbour) whose signs
/// differ although their distances add up to more than a voxel: the surface passes between them
/// with no distance band (issue #27), as where winding numbers alone close a hole.
inline std::size_t bandlessSignJumps(const openvdb::FloatGrid& grid) {
    const double h = grid.voxelSize()[0];
    auto acc = grid.getConstAccessor();
    std::size_t jumps = 0;
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf)
        for (auto v = leaf->cbeginValueAll(); v; ++v)
            for (int axis = 0; axis < 3; ++axis) {
                openvdb::Coord q = v.getCoord();
                q[axis] += 1;
                const float a = *v, b = acc.getValue(q);
                if ((a < 0) != (b < 0) && std::abs(a) + std::abs(b) > 1.01 * h) ++jumps;
            }
    return jumps;
}

}  // namespace jawmesh::test
