// A small labeled jaw made of grid cubes (tests/tet/GridTetMesh.h) and its "input" surfaces as
// boxes that differ from the mesh by known amounts: for evaluation tests that need real distances,
// a crest, and PDLs of known thickness, without TetGen.
#pragma once

#include "io/Case.h"
#include "io/TetMesh.h"
#include "tet/GridTetMesh.h"

#include <algorithm>

namespace jawmesh::test {

constexpr double kJawCellMm = 0.2;
constexpr double kJawCrestZ = 3.6;  // bone top; crowns stick out above it

/// Two teeth (24 and 25) in a bone block 7.2 x 4 x 3.6 mm, each tooth a 1.2 x 1.2 x 4 mm column
/// from z 0.8 to 4.8 with a PDL one cell (0.2 mm) thick around its root, two cells on the +x side
/// of tooth 24. Cells above the bone that are not tooth are left out.
inline TetMesh syntheticJawMesh() {
    const auto inBox = [](const Vec3& p, double x0, double x1, double y0, double y1, double z0, double z1) {
        return p.x() > x0 && p.x() < x1 && p.y() > y0 && p.y() < y1 && p.z() > z0 && p.z() < z1;
    };
    TetMesh m = gridTetMesh(36, 20, 25, kJawCellMm, [&](const Vec3& p) {
        if (inBox(p, 1.4, 2.6, 1.4, 2.6, 0.8, 4.8)) return toothLabel(24);
        if (inBox(p, 4.6, 5.8, 1.4, 2.6, 0.8, 4.8)) return toothLabel(25);
        if (inBox(p, 1.2, 3.0, 1.2, 2.8, 0.6, kJawCrestZ)) return pdlLabel(24);
        if (inBox(p, 4.4, 6.0, 1.2, 2.8, 0.6, kJawCrestZ)) return pdlLabel(25);
        if (p.z() < kJawCrestZ) return kMandibleBoneLabel;
        return kOutsideLabel;
    });
    TetMesh kept;
    kept.nodes = m.nodes;
    for (std::size_t t = 0; t < m.tets.size(); ++t)
        if (m.labels[t] != kOutsideLabel) {
            kept.tets.push_back(m.tets[t]);
            kept.labels.push_back(m.labels[t]);
        }
    return kept;
}

/// Closed outward box surface [lo, hi], each face a grid of squares of about `step` mm split in two.
inline SurfaceMesh boxSurface(const Vec3& lo, const Vec3& hi, double step) {
    SurfaceMesh s;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const int nu = std::max(1, static_cast<int>(std::ceil((hi[u] - lo[u]) / step - 1e-9)));
            const int nv = std::max(1, static_cast<int>(std::ceil((hi[v] - lo[v]) / step - 1e-9)));
            const std::int32_t base = static_cast<std::int32_t>(s.vertices.size());
            for (int j = 0; j <= nv; ++j)
                for (int i = 0; i <= nu; ++i) {
                    Vec3 p;
                    p[axis] = side ? hi[axis] : lo[axis];
                    p[u] = lo[u] + (hi[u] - lo[u]) * i / nu;
                    p[v] = lo[v] + (hi[v] - lo[v]) * j / nv;
                    s.vertices.push_back(p);
                }
            const auto id = [&](int i, int j) { return base + static_cast<std::int32_t>(j * (nu + 1) + i); };
            for (int j = 0; j < nv; ++j)
                for (int i = 0; i < nu; ++i) {
                    // (u, v, axis) is right-handed: counter-clockwise in (u, v) points along +axis.
                    if (side) {
                        s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
                        s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
                    } else {
                        s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
                        s.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
                    }
                }
        }
    return s;
}

/// Input surfaces of the synthetic jaw: tooth boxes 0.05 mm wider on every side, 0.05 mm taller at
/// the crown and 0.1 mm longer at the root; the bone block 0.05 mm higher. Known distances: crown
/// output->input 0.05, input->output up to 0.05 sqrt(3) (top corners); root input->output up to
/// sqrt(0.05^2 + 0.05^2 + 0.1^2) (apex corners).
inline JawSurfaces syntheticJawInput() {
    JawSurfaces in;
    in.jaw = Jaw::Mandible;
    in.bone = boxSurface(Vec3(0, 0, 0), Vec3(7.2, 4.0, kJawCrestZ + 0.05), 0.4);
    in.teeth[24] = boxSurface(Vec3(1.35, 1.35, 0.7), Vec3(2.65, 2.65, 4.85), 0.15);
    in.teeth[25] = boxSurface(Vec3(4.55, 1.35, 0.7), Vec3(5.85, 2.65, 4.85), 0.15);
    return in;
}

}  // namespace jawmesh::test
