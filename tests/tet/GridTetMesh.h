// A structured labeled tet mesh for tests that need a valid mesh without TetGen: a grid of cubes,
// each split into 6 positively oriented tets around its main diagonal (conformal by construction).
#pragma once

#include "io/TetMesh.h"

#include <functional>

namespace jawmesh::test {

/// nx*ny*nz cubes of edge h from the origin; label(cell centre) gives each cube's label.
inline TetMesh gridTetMesh(int nx, int ny, int nz, double h, const std::function<Label(const Vec3&)>& label) {
    TetMesh m;
    auto id = [&](int i, int j, int k) { return static_cast<std::int32_t>((k * (ny + 1) + j) * (nx + 1) + i); };
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) m.nodes.emplace_back(i * h, j * h, k * h);
    // The six monotone paths from corner 000 to 111 (Kuhn triangulation).
    static const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const Label l = label(Vec3((i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h));
                for (const auto& p : paths) {
                    int c[3] = {i, j, k};
                    Tet t;
                    t[0] = id(c[0], c[1], c[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++c[p[s]];
                        t[static_cast<std::size_t>(s) + 1] = id(c[0], c[1], c[2]);
                    }
                    const Vec3& a = m.nodes[static_cast<std::size_t>(t[0])];
                    const double det = (m.nodes[static_cast<std::size_t>(t[1])] - a)
                                           .dot((m.nodes[static_cast<std::size_t>(t[2])] - a).cross(m.nodes[static_cast<std::size_t>(t[3])] - a));
                    if (det < 0) std::swap(t[2], t[3]);
                    m.tets.push_back(t);
                    m.labels.push_back(l);
                }
            }
    return m;
}

}  // namespace jawmesh::test
