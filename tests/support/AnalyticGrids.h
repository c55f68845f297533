// Level sets of analytic shapes for tests: a signed distance function sampled into a narrow band
// (exact values, so a test's expectations are the shape's own), and the distance functions of a
// box and a vertical capsule (the synthetic jaws of the carving and editing tests).
#pragma once

#include <openvdb/openvdb.h>
#include <openvdb/tools/SignedFloodFill.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace jawmesh::test {

using Sdf = std::function<double(const openvdb::Vec3d&)>;

/// f sampled on voxels of voxelMm over [lo, hi] (mm, 5 voxels of margin), band halfWidth voxels.
inline openvdb::FloatGrid::Ptr sampleSdf(const Sdf& f, openvdb::Vec3d lo, openvdb::Vec3d hi, double voxelMm,
                                         double halfWidth = 3.0) {
    const double band = halfWidth * voxelMm;
    auto g = openvdb::FloatGrid::create(float(band));
    g->setTransform(openvdb::math::Transform::createLinearTransform(voxelMm));
    g->setGridClass(openvdb::GRID_LEVEL_SET);
    auto acc = g->getAccessor();
    const auto lower = [&](double x) { return int(std::floor(x / voxelMm)) - 5; };
    const auto upper = [&](double x) { return int(std::ceil(x / voxelMm)) + 5; };
    for (int i = lower(lo[0]); i <= upper(hi[0]); ++i)
        for (int j = lower(lo[1]); j <= upper(hi[1]); ++j)
            for (int k = lower(lo[2]); k <= upper(hi[2]); ++k) {
                const double v = f(openvdb::Vec3d(i, j, k) * voxelMm);
                if (std::abs(v) < band) acc.setValue(openvdb::Coord(i, j, k), float(v));
            }
    openvdb::tools::signedFloodFill(g->tree());
    return g;
}

/// Signed distance to the axis-aligned box [lo, hi].
inline double boxSdf(const openvdb::Vec3d& p, const openvdb::Vec3d& lo, const openvdb::Vec3d& hi) {
    const openvdb::Vec3d c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
    const openvdb::Vec3d q(std::abs(p[0] - c[0]) - h[0], std::abs(p[1] - c[1]) - h[1], std::abs(p[2] - c[2]) - h[2]);
    const openvdb::Vec3d o(std::max(q[0], 0.0), std::max(q[1], 0.0), std::max(q[2], 0.0));
    return o.length() + std::min(std::max({q[0], q[1], q[2]}), 0.0);
}

/// Signed distance to the vertical capsule of radius r around (x, y) from z0 to z1.
inline double capsuleSdf(const openvdb::Vec3d& p, double x, double y, double z0, double z1, double r) {
    const double z = std::clamp(p[2], z0, z1);
    return (p - openvdb::Vec3d(x, y, z)).length() - r;
}

}  // namespace jawmesh::test
