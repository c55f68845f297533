// Exact self-intersection check: configurations decided exactly, speed on a million triangles.
#include "filters/SelfIntersections.h"
#include "io/Error.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

namespace jawmesh {
namespace {

SurfaceMesh uvSphere(int nu, int nv, double r) {
    SurfaceMesh m;
    m.vertices.push_back(Vec3(0, 0, r));
    for (int i = 1; i < nv; ++i)
        for (int j = 0; j < nu; ++j) {
            const double th = M_PI * i / nv, ph = 2 * M_PI * j / nu;
            m.vertices.push_back(r * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
        }
    m.vertices.push_back(Vec3(0, 0, -r));
    const auto id = [&](int i, int j) { return std::int32_t(1 + (i - 1) * nu + (j % nu)); };
    const auto south = std::int32_t(m.vertices.size() - 1);
    for (int j = 0; j < nu; ++j) m.triangles.push_back({0, id(1, j), id(1, j + 1)});
    for (int i = 1; i < nv - 1; ++i)
        for (int j = 0; j < nu; ++j) {
            m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    for (int j = 0; j < nu; ++j) m.triangles.push_back({south, id(nv - 1, j + 1), id(nv - 1, j)});
    return m;
}

TEST(SelfIntersections, PairConfigurations) {
    const Vec3 a[3] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    const Tri ia = {0, 1, 2};
    // piercing
    const Vec3 b[3] = {Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), Vec3(0.3, 0.25, 1)};
    EXPECT_TRUE(trianglesIntersect(a, ia, b, {3, 4, 5}));
    // separate, parallel above
    const Vec3 c[3] = {Vec3(0, 0, 1e-12), Vec3(1, 0, 1e-12), Vec3(0, 1, 1e-12)};
    EXPECT_FALSE(trianglesIntersect(a, ia, c, {3, 4, 5}));
    // touching at a point (vertex on the face) is an intersection
    const Vec3 d[3] = {Vec3(0.25, 0.25, 0), Vec3(0.25, 0.25, 1), Vec3(0.3, 0.2, 1)};
    EXPECT_TRUE(trianglesIntersect(a, ia, d, {3, 4, 5}));
    // shared edge, coplanar, other side: fine; same side: folded
    const Vec3 e[3] = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
    EXPECT_FALSE(trianglesIntersect(a, ia, e, {1, 2, 6}));
    const Vec3 g[3] = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.2, 0.2, 0)};
    EXPECT_TRUE(trianglesIntersect(a, ia, g, {1, 2, 6}));
    // shared vertex, coplanar, disjoint wedges: fine; overlapping wedges: intersect
    const Vec3 h[3] = {Vec3(0, 0, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0)};
    EXPECT_FALSE(trianglesIntersect(a, ia, h, {0, 7, 8}));
    const Vec3 k[3] = {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 0.5, 0)};
    EXPECT_TRUE(trianglesIntersect(a, ia, k, {0, 7, 8}));
    // shared vertex, non-coplanar, crossing through the face
    const Vec3 m[3] = {Vec3(0, 0, 0), Vec3(0.3, 0.3, 1), Vec3(0.3, 0.3, -1)};
    EXPECT_TRUE(trianglesIntersect(a, ia, m, {0, 7, 8}));
    // decided exactly: a corner 1e-300 mm above the face does not touch it, at 0 it does
    const Vec3 n[3] = {Vec3(0.25, 0.25, 1e-300), Vec3(0.25, 0.25, 1), Vec3(0.3, 0.25, 1)};
    EXPECT_FALSE(trianglesIntersect(a, ia, n, {3, 4, 5}));
    const Vec3 o[3] = {Vec3(0.25, 0.25, 0), Vec3(0.25, 0.25, 1), Vec3(0.3, 0.25, 1)};
    EXPECT_TRUE(trianglesIntersect(a, ia, o, {3, 4, 5}));
}

TEST(SelfIntersections, CleanSphereAndDentedSphere) {
    SurfaceMesh s = uvSphere(64, 32, 1.0);
    EXPECT_TRUE(findSelfIntersections(s).clean());
    // push one vertex through the opposite side
    s.vertices[1 + 10 * 64 + 5] *= -1.2;
    EXPECT_FALSE(findSelfIntersections(s).pairs.empty());
    // duplicate triangle and degenerate triangle
    SurfaceMesh t = uvSphere(16, 8, 1.0);
    t.triangles.push_back(t.triangles[3]);
    t.triangles.push_back({0, 0, 1});
    const auto r = findSelfIntersections(t);
    EXPECT_FALSE(r.pairs.empty());
    EXPECT_EQ(r.degenerate.size(), 1u);
    // The degenerate one meets every triangle at vertex 0 but is never a pair (it is reported as
    // degenerate); this used to read past the corner arrays (AddressSanitizer).
    for (const auto& [x, y] : r.pairs) {
        EXPECT_NE(x, std::int32_t(t.triangles.size() - 1));
        EXPECT_NE(y, std::int32_t(t.triangles.size() - 1));
    }
    const Vec3 d[3] = {t.vertices[0], t.vertices[0], t.vertices[1]};
    for (std::size_t k = 0; k + 1 < t.triangles.size(); ++k) {
        const Tri& f = t.triangles[k];
        const Vec3 p[3] = {t.vertices[f[0]], t.vertices[f[1]], t.vertices[f[2]]};
        EXPECT_FALSE(trianglesIntersect(d, {0, 0, 1}, p, f));
        EXPECT_FALSE(trianglesIntersect(p, f, d, {0, 0, 1}));
    }
}

// With flags, only pairs that have a flagged triangle are tested (a surface changed in places).
TEST(SelfIntersections, OnlyPairsWithAFlaggedTriangle) {
    SurfaceMesh s = uvSphere(64, 32, 1.0);
    const std::int32_t pushed = 1 + 10 * 64 + 5;
    s.vertices[std::size_t(pushed)] *= -1.2;
    const auto all = findSelfIntersections(s);
    ASSERT_FALSE(all.pairs.empty());
    std::vector<char> atPushed(s.triangles.size(), 0), elsewhere(s.triangles.size(), 0);
    std::vector<char> flagged = atPushed;
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        const Tri& f = s.triangles[t];
        const bool at = f[0] == pushed || f[1] == pushed || f[2] == pushed;
        atPushed[t] = at;
        bool inPair = false;
        for (const auto& [a, b] : all.pairs) inPair = inPair || a == std::int32_t(t) || b == std::int32_t(t);
        elsewhere[t] = !inPair;
    }
    // every intersecting pair has a triangle at the pushed vertex: flagging those finds them all
    EXPECT_EQ(findSelfIntersections(s, &atPushed).pairs, all.pairs);
    EXPECT_TRUE(findSelfIntersections(s, &elsewhere).pairs.empty());
    // any flags: exactly the pairs of the whole check that have a flagged triangle
    std::mt19937 random(7);
    for (int round = 0; round < 5; ++round) {
        std::vector<char> some(s.triangles.size(), 0);
        for (char& f : some) f = random() % 10 == 0;
        for (const auto& [a, b] : all.pairs)
            if (random() % 3 == 0) some[std::size_t(a)] = 1;  // some pairs in, some half in, some out
        std::vector<std::pair<std::int32_t, std::int32_t>> expected;
        for (const auto& p : all.pairs)
            if (some[std::size_t(p.first)] || some[std::size_t(p.second)]) expected.push_back(p);
        EXPECT_EQ(findSelfIntersections(s, &some).pairs, expected);
    }
    std::vector<char> wrongSize(3, 1);
    EXPECT_THROW(findSelfIntersections(s, &wrongSize), Error);
}

// A dense closed surface (many near-coplanar neighbours) is clean; speed is a bench/ matter.
TEST(SelfIntersections, DenseSphereIsClean) {
    const SurfaceMesh s = uvSphere(300, 150, 10.0);
    ASSERT_GT(s.triangles.size(), 80000u);
    EXPECT_TRUE(findSelfIntersections(s).clean());
}

}  // namespace
}  // namespace jawmesh
