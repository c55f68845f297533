// Three-triangle corners of a region are split away without moving the surface.
#include "filters/SplitCorners.h"
#include "io/Labels.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace jawmesh {
namespace {

/// Two tets glued on triangle 012: region A above (apex 3), region B below (apex 4). Every
/// vertex starts with three triangles of some region.
InterfaceComplex bipyramid() {
    InterfaceComplex c;
    c.surface.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0.5, 0.5, 1.5), Vec3(0.6, 0.4, -1.2)};
    const Label A = toothLabel(24), B = pdlLabel(24);
    c.surface.triangles = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {1, 0, 4}, {2, 1, 4}, {0, 2, 4}, {0, 2, 1}};
    c.sides = {{kOutsideLabel, A}, {kOutsideLabel, A}, {kOutsideLabel, A}, {kOutsideLabel, B},
               {kOutsideLabel, B}, {kOutsideLabel, B}, {A, B}};
    return c;
}

double area(const InterfaceComplex& c, std::size_t t) {
    const auto& f = c.surface.triangles[t];
    const auto& V = c.surface.vertices;
    return 0.5 * (V[std::size_t(f[1])] - V[std::size_t(f[0])]).cross(V[std::size_t(f[2])] - V[std::size_t(f[0])]).norm();
}

/// Per label pair: total area and the sum of unit normals times area (orientation kept).
std::map<std::pair<Label, Label>, Vec3> weightedNormals(const InterfaceComplex& c) {
    std::map<std::pair<Label, Label>, Vec3> out;
    const auto& V = c.surface.vertices;
    for (std::size_t t = 0; t < c.sides.size(); ++t) {
        const auto& f = c.surface.triangles[t];
        const Vec3 n = 0.5 * (V[std::size_t(f[1])] - V[std::size_t(f[0])]).cross(V[std::size_t(f[2])] - V[std::size_t(f[0])]);
        auto [it, fresh] = out.try_emplace({c.sides[t][0], c.sides[t][1]}, Vec3::Zero());
        it->second += n;
    }
    return out;
}

TEST(SplitCorners, EveryRegionGetsFourTrianglesAtEveryVertexAndNothingMoves) {
    const InterfaceComplex before = bipyramid();
    InterfaceComplex c = before;
    const std::size_t splits = splitThreeTriangleCorners(c);
    EXPECT_GT(splits, 0u);
    // old vertices unmoved, new ones on the midpoint of two old-or-new vertices (on the surface)
    for (std::size_t v = 0; v < before.surface.vertices.size(); ++v) EXPECT_EQ(c.surface.vertices[v], before.surface.vertices[v]);
    EXPECT_EQ(c.surface.vertices.size(), before.surface.vertices.size() + splits);
    // at least four triangles of each region at each vertex
    std::map<std::pair<std::int32_t, Label>, int> count;
    for (std::size_t t = 0; t < c.sides.size(); ++t)
        for (Label L : c.sides[t])
            if (L != kOutsideLabel)
                for (auto v : c.surface.triangles[t]) count[{v, L}]++;
    for (const auto& [key, n] : count) EXPECT_GE(n, 4) << "vertex " << key.first << " region " << labelName(key.second);
    // same oriented area per interface; every edge still has two triangles per interface pair
    const auto n0 = weightedNormals(before), n1 = weightedNormals(c);
    ASSERT_EQ(n0.size(), n1.size());
    for (const auto& [pair, n] : n0) EXPECT_LT((n1.at(pair) - n).norm(), 1e-12);
    double a0 = 0, a1 = 0;
    for (std::size_t t = 0; t < before.sides.size(); ++t) a0 += area(before, t);
    for (std::size_t t = 0; t < c.sides.size(); ++t) a1 += area(c, t);
    EXPECT_NEAR(a1, a0, 1e-12);
    std::map<std::pair<int, int>, int> edgeUse;
    for (const auto& f : c.surface.triangles)
        for (int k = 0; k < 3; ++k) edgeUse[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}]++;
    for (const auto& [e, n] : edgeUse) EXPECT_TRUE(n == 2 || n == 3) << e.first << "-" << e.second;  // 3 on the A/B rim
    // already fine: nothing to do
    InterfaceComplex again = c;
    EXPECT_EQ(splitThreeTriangleCorners(again), 0u);
    EXPECT_EQ(again.surface.triangles, c.surface.triangles);
}

}  // namespace
}  // namespace jawmesh
