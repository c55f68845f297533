// Implements filters/NearTeeth.h; what it computes, its rules and its contract are documented there.
#include "filters/NearTeeth.h"

#include "io/Labels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace jawmesh {

namespace {

bool touchesTooth(const std::array<Label, 2>& sides) {
    for (Label l : sides) {
        if (l == kOutsideLabel) continue;
        const LabelKind k = labelKind(l);
        if (isToothLike(k) || k == LabelKind::Pdl) return true;
    }
    return false;
}

/// Dilates a dense 0/1 grid by `r` cells along one axis (a running window maximum).
void dilateAxis(std::vector<char>& g, const std::array<std::int64_t, 3>& dim, int axis, std::int64_t r) {
    const std::int64_t stride = axis == 0 ? 1 : axis == 1 ? dim[0] : dim[0] * dim[1];
    const std::int64_t n = dim[std::size_t(axis)];
    const std::int64_t lines = dim[0] * dim[1] * dim[2] / n;
    std::vector<char> line(static_cast<std::size_t>(n)), out(static_cast<std::size_t>(n));
    for (std::int64_t l = 0; l < lines; ++l) {
        // base index of line l: enumerate the two other axes
        std::int64_t base;
        if (axis == 0) base = l * dim[0];
        else if (axis == 1) base = (l / dim[0]) * dim[0] * dim[1] + (l % dim[0]);
        else base = l;
        bool any = false;
        for (std::int64_t i = 0; i < n; ++i) any |= (line[std::size_t(i)] = g[std::size_t(base + i * stride)]) != 0;
        if (!any) continue;
        std::int64_t last = -(r + 1);  // last set cell seen, scanning forward
        for (std::int64_t i = 0; i < n; ++i) {
            if (line[std::size_t(i)]) last = i;
            out[std::size_t(i)] = i - last <= r;
        }
        last = n + r + 1;
        for (std::int64_t i = n - 1; i >= 0; --i) {
            if (line[std::size_t(i)]) last = i;
            if (last - i <= r) out[std::size_t(i)] = 1;
        }
        for (std::int64_t i = 0; i < n; ++i) g[std::size_t(base + i * stride)] = out[std::size_t(i)];
    }
}

}  // namespace

std::vector<char> verticesNearTeeth(const InterfaceComplex& complex, double distanceMm) {
    const auto& V = complex.surface.vertices;
    const auto& T = complex.surface.triangles;
    std::vector<char> near(V.size(), 0);
    for (std::size_t t = 0; t < T.size(); ++t)
        if (touchesTooth(complex.sides[t]))
            for (auto v : T[t]) near[std::size_t(v)] = 1;
    if (!(distanceMm > 0) || V.empty()) return near;

    Vec3 lo = V[0], hi = V[0];
    for (const Vec3& p : V) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    double cell = distanceMm / 4.0;
    const auto cellsFor = [&](double c) {
        std::array<std::int64_t, 3> d;
        for (int k = 0; k < 3; ++k) d[std::size_t(k)] = std::int64_t(std::floor((hi[k] - lo[k]) / c)) + 1;
        return d;
    };
    std::array<std::int64_t, 3> dim = cellsFor(cell);
    while (double(dim[0]) * double(dim[1]) * double(dim[2]) > 64e6) dim = cellsFor(cell *= 1.25);
    const auto index = [&](const Vec3& p) {
        std::int64_t i[3];
        for (int k = 0; k < 3; ++k)
            i[k] = std::clamp<std::int64_t>(std::int64_t(std::floor((p[k] - lo[k]) / cell)), 0, dim[std::size_t(k)] - 1);
        return std::size_t(i[0] + dim[0] * (i[1] + dim[1] * i[2]));
    };
    std::vector<char> grid(std::size_t(dim[0] * dim[1] * dim[2]), 0);
    for (std::size_t v = 0; v < V.size(); ++v)
        if (near[v]) grid[index(V[v])] = 1;
    const std::int64_t r = std::int64_t(std::ceil(distanceMm / cell));
    for (int axis = 0; axis < 3; ++axis) dilateAxis(grid, dim, axis, r);
    for (std::size_t v = 0; v < V.size(); ++v)
        if (grid[index(V[v])]) near[v] = 1;
    return near;
}

}  // namespace jawmesh
