// Implements levelset/PhantomSurface.h; what it computes, its rules and its contract are documented there.
#include "levelset/PhantomSurface.h"

#include "io/Error.h"
#include "io/VertexTriangles.h"
#include "levelset/PhantomRandom.h"

#include <openvdb/tools/SignedFloodFill.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace jawmesh::phantom {

openvdb::FloatGrid::Ptr sampleLevelSet(const std::function<double(const Vec3&)>& field, const BBox& box,
                                       double voxelMm, double lipschitz) {
    using LeafT = openvdb::FloatTree::LeafNodeType;
    const double band = 3.0 * voxelMm;
    auto grid = openvdb::FloatGrid::create(static_cast<float>(band));
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxelMm));
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    if (box.empty()) return grid;

    // Leaf-aligned block origins covering the box.
    auto lo = [&](double x) { return static_cast<int>(std::floor(std::floor(x / voxelMm) / 8.0)) * 8; };
    const int x0 = lo(box.min.x()), y0 = lo(box.min.y()), z0 = lo(box.min.z());
    const int nx = (lo(box.max.x()) - x0) / 8 + 1, ny = (lo(box.max.y()) - y0) / 8 + 1, nz = (lo(box.max.z()) - z0) / 8 + 1;
    const std::size_t blocks = static_cast<std::size_t>(nx) * ny * nz;
    auto origin = [&](std::size_t b) {
        const int i = static_cast<int>(b % nx), j = static_cast<int>((b / nx) % ny), k = static_cast<int>(b / (static_cast<std::size_t>(nx) * ny));
        return openvdb::Coord(x0 + 8 * i, y0 + 8 * j, z0 + 8 * k);
    };

    // Pass 1: which blocks can touch the band (the field changes by at most lipschitz per mm).
    const double reach = lipschitz * 3.5 * std::sqrt(3.0) * voxelMm + band;
    std::vector<char> near(blocks, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
            const openvdb::Coord o = origin(b);
            const Vec3 c = (Vec3(o.x(), o.y(), o.z()) + Vec3::Constant(3.5)) * voxelMm;
            near[b] = std::abs(field(c)) <= reach;
        }
    });
    std::vector<std::size_t> todo;
    for (std::size_t b = 0; b < blocks; ++b)
        if (near[b]) todo.push_back(b);

    // Pass 2: those blocks, refined through 4^3 and 2^3 sub-blocks that are skipped (filled with
    // +-band, inactive) when their centre is too far from the zero set; leaves without band voxels
    // are dropped.
    std::vector<std::unique_ptr<LeafT>> leaves(todo.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            const openvdb::Coord o = origin(todo[t]);
            auto leaf = std::make_unique<LeafT>(o, static_cast<float>(band));
            bool any = false;
            auto voxel = [&](int i, int j, int k, double v) {
                const openvdb::Index n = LeafT::coordToOffset(openvdb::Coord(o.x() + i, o.y() + j, o.z() + k));
                if (std::abs(v) < band) {
                    leaf->setValueOn(n, static_cast<float>(v));
                    any = true;
                } else {
                    leaf->setValueOff(n, static_cast<float>(v < 0 ? -band : band));
                }
            };
            std::function<void(int, int, int, int)> cube = [&](int i, int j, int k, int size) {
                if (size == 1) {
                    voxel(i, j, k, field(Vec3(o.x() + i, o.y() + j, o.z() + k) * voxelMm));
                    return;
                }
                const double h = (size - 1) / 2.0;
                const double c = field(Vec3(o.x() + i + h, o.y() + j + h, o.z() + k + h) * voxelMm);
                if (std::abs(c) > lipschitz * h * std::sqrt(3.0) * voxelMm + band) {
                    for (int a = 0; a < size; ++a)
                        for (int b = 0; b < size; ++b)
                            for (int d = 0; d < size; ++d) voxel(i + a, j + b, k + d, c);
                    return;
                }
                const int s2 = size / 2;
                for (int a = 0; a < 2; ++a)
                    for (int b = 0; b < 2; ++b)
                        for (int d = 0; d < 2; ++d) cube(i + a * s2, j + b * s2, k + d * s2, s2);
            };
            for (int a = 0; a < 2; ++a)
                for (int b = 0; b < 2; ++b)
                    for (int d = 0; d < 2; ++d) cube(4 * a, 4 * b, 4 * d, 4);
            if (any) leaves[t] = std::move(leaf);
        }
    });
    auto& tree = grid->tree();
    for (auto& leaf : leaves)
        if (leaf) tree.addLeaf(leaf.release());
    openvdb::tools::signedFloodFill(tree);
    return grid;
}

void jitterTangentially(SurfaceMesh& mesh, double amplitudeMm, std::uint64_t seed) {
    auto& V = mesh.vertices;
    const auto& F = mesh.triangles;
    const std::size_t nv = V.size();
    const VertexTriangles around = vertexTriangles(F, nv);

    auto normal = [&](const Tri& t) -> Vec3 { return (V[t[1]] - V[t[0]]).cross(V[t[2]] - V[t[0]]); };
    const double cosLimit = 0.5;
    for (std::size_t i = 0; i < nv; ++i) {
        const auto vi = static_cast<std::int32_t>(i);
        Vec3 n = Vec3::Zero();
        for (const std::int32_t* f = around.begin(vi); f != around.end(vi); ++f) n += normal(F[static_cast<std::size_t>(*f)]);
        if (n.squaredNorm() == 0) continue;
        n.normalize();
        const std::uint64_t h = splitMix64(seed ^ splitMix64(i));
        Vec3 r(unitFromHash(h), unitFromHash(splitMix64(h + 1)), unitFromHash(splitMix64(h + 2)));
        r -= r.dot(n) * n;
        const Vec3 old = V[i];
        std::vector<Vec3> before;
        for (const std::int32_t* f = around.begin(vi); f != around.end(vi); ++f) before.push_back(normal(F[static_cast<std::size_t>(*f)]));
        for (double scale : {1.0, 0.5, 0.0}) {
            V[i] = old + r * (amplitudeMm * scale);
            bool ok = true;
            for (const std::int32_t* f = around.begin(vi); f != around.end(vi) && ok; ++f) {
                const Vec3 a = before[static_cast<std::size_t>(f - around.begin(vi))], b = normal(F[static_cast<std::size_t>(*f)]);
                ok = a.dot(b) > cosLimit * a.norm() * b.norm();
            }
            if (ok) break;
        }
    }
}

}  // namespace jawmesh::phantom
