// Implements the test helpers of tet/TetTestComplexes.h (documented there).
#include "tet/TetTestComplexes.h"

#include "support/Icosphere.h"

#include <Eigen/Geometry>

#include <cmath>
#include <queue>

namespace jawmesh::test {

Label VoxelScene::at(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return kOutsideLabel;
    return labels[static_cast<std::size_t>((k * ny + j) * nx + i)];
}

VoxelScene jawBlockScene(double h) {
    VoxelScene s;
    s.nx = 16, s.ny = 8, s.nz = 12, s.h = h;
    s.labels.assign(static_cast<std::size_t>(s.nx * s.ny * s.nz), kOutsideLabel);
    struct ToothBox { int unn, x0, x1, y0, y1; };
    const ToothBox teeth[] = {{24, 4, 6, 3, 5}, {25, 10, 12, 3, 5}};
    for (int k = 0; k < s.nz; ++k)
        for (int j = 0; j < s.ny; ++j)
            for (int i = 0; i < s.nx; ++i) {
                Label l = k < 8 ? kMandibleBoneLabel : kOutsideLabel;
                for (const auto& t : teeth) {
                    const bool inRoot = i >= t.x0 && i < t.x1 && j >= t.y0 && j < t.y1 && k >= 3 && k < 11;
                    const bool nearRoot = i >= t.x0 - 1 && i < t.x1 + 1 && j >= t.y0 - 1 && j < t.y1 + 1 && k >= 2 && k < 8;
                    if (inRoot) l = toothLabel(t.unn);
                    else if (nearRoot) l = pdlLabel(t.unn);
                }
                s.labels[static_cast<std::size_t>((k * s.ny + j) * s.nx + i)] = l;
            }
    return s;
}

InterfaceComplex complexFromVoxels(const VoxelScene& s) {
    InterfaceComplex c;
    std::vector<std::int32_t> vertexOf(static_cast<std::size_t>((s.nx + 1) * (s.ny + 1) * (s.nz + 1)), -1);
    auto vertex = [&](int i, int j, int k) {
        auto& v = vertexOf[static_cast<std::size_t>((k * (s.ny + 1) + j) * (s.nx + 1) + i)];
        if (v < 0) {
            v = static_cast<std::int32_t>(c.surface.vertices.size());
            c.surface.vertices.emplace_back(i * s.h, j * s.h, k * s.h);
        }
        return v;
    };
    // Face between cell (i,j,k) - e_axis and (i,j,k); corners listed counter-clockwise about +axis.
    auto quad = [&](int axis, int i, int j, int k) {
        const Label lower = s.at(i - (axis == 0), j - (axis == 1), k - (axis == 2));
        const Label upper = s.at(i, j, k);
        if (lower == upper) return;
        std::array<std::int32_t, 4> q;
        if (axis == 0) q = {vertex(i, j, k), vertex(i, j + 1, k), vertex(i, j + 1, k + 1), vertex(i, j, k + 1)};
        else if (axis == 1) q = {vertex(i, j, k), vertex(i, j, k + 1), vertex(i + 1, j, k + 1), vertex(i + 1, j, k)};
        else q = {vertex(i, j, k), vertex(i + 1, j, k), vertex(i + 1, j + 1, k), vertex(i, j + 1, k)};
        c.surface.triangles.push_back({q[0], q[1], q[2]});
        c.surface.triangles.push_back({q[0], q[2], q[3]});
        c.sides.push_back({upper, lower});  // normal +axis points into the upper cell
        c.sides.push_back({upper, lower});
    };
    for (int k = 0; k <= s.nz; ++k)
        for (int j = 0; j <= s.ny; ++j)
            for (int i = 0; i <= s.nx; ++i) {
                if (j < s.ny && k < s.nz) quad(0, i, j, k);
                if (i < s.nx && k < s.nz) quad(1, i, j, k);
                if (i < s.nx && j < s.ny) quad(2, i, j, k);
            }
    // One seed per connected component (flood fill), at a voxel centre.
    std::vector<char> seen(s.labels.size(), 0);
    for (int k = 0; k < s.nz; ++k)
        for (int j = 0; j < s.ny; ++j)
            for (int i = 0; i < s.nx; ++i) {
                const auto idx = static_cast<std::size_t>((k * s.ny + j) * s.nx + i);
                const Label l = s.labels[idx];
                if (seen[idx] || l == kOutsideLabel) continue;
                c.seeds.push_back({Vec3((i + 0.5) * s.h, (j + 0.5) * s.h, (k + 0.5) * s.h), l});
                std::queue<std::array<int, 3>> q;
                q.push({i, j, k});
                seen[idx] = 1;
                while (!q.empty()) {
                    const auto p = q.front();
                    q.pop();
                    const int d[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
                    for (const auto& e : d) {
                        const int a = p[0] + e[0], b = p[1] + e[1], cc = p[2] + e[2];
                        if (s.at(a, b, cc) != l) continue;
                        const auto n = static_cast<std::size_t>((cc * s.ny + b) * s.nx + a);
                        if (seen[n]) continue;
                        seen[n] = 1;
                        q.push({a, b, cc});
                    }
                }
            }
    return c;
}

std::map<Label, double> voxelVolumes(const VoxelScene& s) {
    std::map<Label, double> v;
    for (Label l : s.labels)
        if (l != kOutsideLabel) v[l] += s.h * s.h * s.h;
    return v;
}

std::map<Label, double> complexVolumes(const InterfaceComplex& c) {
    std::map<Label, double> v;
    for (std::size_t t = 0; t < c.surface.triangles.size(); ++t) {
        const auto& tri = c.surface.triangles[t];
        const Vec3& a = c.surface.vertices[static_cast<std::size_t>(tri[0])];
        const Vec3& b = c.surface.vertices[static_cast<std::size_t>(tri[1])];
        const Vec3& d = c.surface.vertices[static_cast<std::size_t>(tri[2])];
        const double vol = a.dot(b.cross(d)) / 6.0;
        // The normal points out of sides[1] (outward for it) and into sides[0].
        if (c.sides[t][1] != kOutsideLabel) v[c.sides[t][1]] += vol;
        if (c.sides[t][0] != kOutsideLabel) v[c.sides[t][0]] -= vol;
    }
    return v;
}

namespace {

/// A closed box whose faces share their edge vertices (test::boxSurface keeps them apart).
SurfaceMesh weldedBoxSurface(const Vec3& lo, const Vec3& hi, double spacing) {
    SurfaceMesh m;
    std::map<std::array<long, 3>, int> index;
    const Vec3 size = hi - lo;
    std::array<int, 3> n;
    for (int a = 0; a < 3; ++a) n[static_cast<std::size_t>(a)] = std::max(1, static_cast<int>(std::lround(size[a] / spacing)));
    auto vertex = [&](std::array<int, 3> g) {
        const std::array<long, 3> key = {g[0], g[1], g[2]};
        auto it = index.find(key);
        if (it != index.end()) return it->second;
        Vec3 p;
        for (int a = 0; a < 3; ++a) p[a] = lo[a] + size[a] * g[static_cast<std::size_t>(a)] / n[static_cast<std::size_t>(a)];
        m.vertices.push_back(p);
        return index[key] = static_cast<int>(m.vertices.size() - 1);
    };
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side)
            for (int i = 0; i < n[static_cast<std::size_t>(u)]; ++i)
                for (int j = 0; j < n[static_cast<std::size_t>(v)]; ++j) {
                    std::array<std::array<int, 3>, 4> g;
                    const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
                    for (int c = 0; c < 4; ++c) {
                        g[static_cast<std::size_t>(c)][static_cast<std::size_t>(axis)] = side ? n[static_cast<std::size_t>(axis)] : 0;
                        g[static_cast<std::size_t>(c)][static_cast<std::size_t>(u)] = i + di[c];
                        g[static_cast<std::size_t>(c)][static_cast<std::size_t>(v)] = j + dj[c];
                    }
                    int q[4];
                    for (int c = 0; c < 4; ++c) q[c] = vertex(g[static_cast<std::size_t>(c)]);
                    // u x v = +axis: counter-clockwise is outward on the high side.
                    if (side) {
                        m.triangles.push_back({q[0], q[1], q[2]});
                        m.triangles.push_back({q[0], q[2], q[3]});
                    } else {
                        m.triangles.push_back({q[0], q[2], q[1]});
                        m.triangles.push_back({q[0], q[3], q[2]});
                    }
                }
    }
    return m;
}

/// Adds `surface` (outward for `inside`) to the complex with sides {outside, inside}.
void addSurface(InterfaceComplex& c, const SurfaceMesh& surface, Label inside, Label outside) {
    append(c.surface, surface);
    for (std::size_t t = 0; t < surface.triangles.size(); ++t) c.sides.push_back({outside, inside});
}

}  // namespace

InterfaceComplex nestedSpheresComplex(int subdivisions, double boxSpacing) {
    InterfaceComplex c;
    const Label bone = kMandibleBoneLabel;
    addSurface(c, weldedBoxSurface(Vec3(-4, -2.5, -2.5), Vec3(4, 2.5, 2.5), boxSpacing), bone, kOutsideLabel);
    const struct { int unn; double x; } teeth[] = {{24, -1.7}, {25, 1.7}};
    for (const auto& t : teeth) {
        addSurface(c, test::icosphere(1.3, subdivisions, Vec3(t.x, 0, 0)), pdlLabel(t.unn), bone);
        addSurface(c, test::icosphere(1.0, subdivisions, Vec3(t.x, 0, 0)), toothLabel(t.unn), pdlLabel(t.unn));
        c.seeds.push_back({Vec3(t.x, 0, 0), toothLabel(t.unn)});
        c.seeds.push_back({Vec3(t.x, 0, 1.15), pdlLabel(t.unn)});
    }
    c.seeds.push_back({Vec3(-3.8, -2.3, -2.3), bone});
    return c;
}

InterfaceComplex thinPdlComplex(double thicknessMm, int subdivisions) {
    InterfaceComplex c;
    const Label bone = kMandibleBoneLabel;
    addSurface(c, weldedBoxSurface(Vec3(-2, -2, -2), Vec3(2, 2, 2), 0.5), bone, kOutsideLabel);
    SurfaceMesh outer = test::icosphere(1.0 + thicknessMm, subdivisions);
    // turned about an oblique axis: no node of the root faces one of the socket straight on
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    for (Vec3& v : outer.vertices) v = turn * v;
    addSurface(c, outer, pdlLabel(24), bone);
    addSurface(c, test::icosphere(1.0, subdivisions), toothLabel(24), pdlLabel(24));
    c.seeds.push_back({Vec3::Zero(), toothLabel(24)});
    c.seeds.push_back({Vec3(0, 0, 1.0 + 0.5 * thicknessMm), pdlLabel(24)});
    c.seeds.push_back({Vec3(-1.9, -1.9, -1.9), bone});
    return c;
}

}  // namespace jawmesh::test
