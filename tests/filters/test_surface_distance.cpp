// TriangleBvh, sampleDistances/summarizeDistances and weighted distributions on generated spheres:
// nearest triangles equal brute force, maxima agree with the analytic distance between two offset
// spheres, results do not depend on the thread count.
#include "filters/SurfaceDistance.h"
#include "filters/TriangleGeometry.h"
#include "filters/WeightedDistribution.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace jawmesh;

namespace {

/// UV sphere of radius r around c, `rings` x 2 `rings` quads split in two (poles as fans).
SurfaceMesh sphere(const Vec3& c, double r, int rings) {
    SurfaceMesh s;
    const int segments = 2 * rings;
    s.vertices.push_back(c + Vec3(0, 0, r));
    for (int i = 1; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double th = M_PI * i / rings, ph = 2 * M_PI * j / segments;
            s.vertices.push_back(c + r * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
        }
    s.vertices.push_back(c + Vec3(0, 0, -r));
    const auto id = [&](int i, int j) { return static_cast<std::int32_t>(1 + (i - 1) * segments + (j % segments)); };
    const std::int32_t south = static_cast<std::int32_t>(s.vertices.size() - 1);
    for (int j = 0; j < segments; ++j) {
        s.triangles.push_back({0, id(1, j), id(1, j + 1)});
        s.triangles.push_back({south, id(rings - 1, j + 1), id(rings - 1, j)});
        for (int i = 1; i + 1 < rings; ++i) {
            s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    }
    return s;
}

}  // namespace

TEST(TriangleBvh, NearestTriangleEqualsBruteForce) {
    const SurfaceMesh s = sphere(Vec3(1, 2, 3), 5.0, 40);
    const TriangleBvh bvh = buildTriangleBvh(s);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-9, 9);
    for (int k = 0; k < 300; ++k) {
        const Vec3 p = Vec3(1, 2, 3) + Vec3(u(rng), u(rng), u(rng));
        double best = INFINITY;
        std::int32_t bestTri = -1;
        for (std::size_t t = 0; t < s.triangles.size(); ++t) {
            const Tri& tri = s.triangles[t];
            const double d2 = squaredDistanceToTriangle(p, s.vertices[static_cast<std::size_t>(tri[0])],
                                                        s.vertices[static_cast<std::size_t>(tri[1])], s.vertices[static_cast<std::size_t>(tri[2])]);
            if (d2 < best) {
                best = d2;
                bestTri = static_cast<std::int32_t>(t);
            }
        }
        const ClosestTriangle c = closestTriangle(bvh, p, k % 2 ? static_cast<std::int32_t>(k) : -1);
        EXPECT_EQ(c.squaredDistanceMm2, best);
        EXPECT_EQ(c.triangle, bestTri);  // lowest index on ties, as the brute force loop keeps it
    }
    // A vertex shared by several triangles: the tie goes to the lowest triangle index.
    const ClosestTriangle pole = closestTriangle(bvh, s.vertices[0] + Vec3(0, 0, 1));
    EXPECT_EQ(pole.triangle, 0);
    EXPECT_TRUE(closestTriangle(buildTriangleBvh(SurfaceMesh{}), Vec3::Zero()).triangle == -1);
}

TEST(TriangleBvh, WalkToANearbyTriangleBoundsTheNearestAndReachesItOnASphere) {
    const SurfaceMesh s = sphere(Vec3(1, 2, 3), 5.0, 40);
    const TriangleBvh bvh = buildTriangleBvh(s);
    // Every inner edge of the closed sphere has its neighbour, and neighbours share both vertices.
    for (std::size_t slot = 0; slot < bvh.edgeNeighbour.size(); ++slot)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::int32_t o = bvh.edgeNeighbour[slot][k];
            ASSERT_GE(o, 0);
            const Tri& t = s.triangles[static_cast<std::size_t>(bvh.triangle[slot])];
            const Tri& u = s.triangles[static_cast<std::size_t>(bvh.triangle[static_cast<std::size_t>(o)])];
            for (std::int32_t v : {t[k], t[(k + 1) % 3]}) EXPECT_NE(std::find(u.begin(), u.end(), v), u.end());
        }
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int reached = 0;
    for (int k = 0; k < 300; ++k) {
        Vec3 dir(u(rng), u(rng), u(rng));
        if (dir.norm() < 0.1) continue;
        const Vec3 p = Vec3(1, 2, 3) + (5.0 + 0.3 * u(rng)) * dir.normalized();
        const ClosestTriangle exact = closestTriangle(bvh, p);
        // From a triangle a few rings away: an upper bound always, the nearest on this convex surface.
        const Vec3 q = Vec3(1, 2, 3) + 5.0 * (dir.normalized() + 0.15 * Vec3(u(rng), u(rng), u(rng))).normalized();
        const ClosestTriangle walked = nearbyTriangle(bvh, p, closestTriangle(bvh, q).triangle, 64);
        EXPECT_GE(walked.squaredDistanceMm2, exact.squaredDistanceMm2);
        reached += walked.squaredDistanceMm2 == exact.squaredDistanceMm2;
    }
    EXPECT_GE(reached, 280);
    // Without steps it is the start triangle's own distance; no start, no answer.
    const ClosestTriangle stay = nearbyTriangle(bvh, Vec3(20, 0, 0), 7, 0);
    EXPECT_EQ(stay.triangle, 7);
    EXPECT_EQ(nearbyTriangle(bvh, Vec3::Zero(), -1).triangle, -1);
}

TEST(SurfaceDistance, OffsetSpheresGiveTheAnalyticDistances) {
    // Sphere B is sphere A moved by 0.3 along x: the distance from a point of A to B is
    // |  |p - cB| - r  |, largest (0.3) at the two points on the x axis.
    const double r = 10, shift = 0.3;
    const SurfaceMesh a = sphere(Vec3::Zero(), r, 48), b = sphere(Vec3(shift, 0, 0), r, 96);
    const TriangleBvh bvhB = buildTriangleBvh(b);
    const DistanceSamples samples = sampleDistances(a, bvhB, 0.5);
    ASSERT_EQ(static_cast<std::size_t>(samples.firstOfTriangle.back()), samples.distanceMm.size());
    double area = 0;
    for (double w : samples.weightMm2) area += w;
    double exactArea = 0;
    for (const Tri& t : a.triangles)
        exactArea += 0.5 * (a.vertices[static_cast<std::size_t>(t[1])] - a.vertices[static_cast<std::size_t>(t[0])])
                               .cross(a.vertices[static_cast<std::size_t>(t[2])] - a.vertices[static_cast<std::size_t>(t[0])])
                               .norm();
    EXPECT_NEAR(area, exactArea, 1e-9 * exactArea);

    const std::vector<int> group(a.triangles.size(), 0);
    const DistanceSummary s = summarizeDistances(a, samples, group, 1, bvhB, 1e-4).front();
    // Faceting moves the surfaces inwards by at most the sagitta of each triangle's circumcircle:
    // A's points gain up to A's depth, B's facets take away up to B's.
    const auto depth = [&](const SurfaceMesh& m) {
        double worst = 0;
        for (const Tri& t : m.triangles) {
            const Vec3 p0 = m.vertices[static_cast<std::size_t>(t[0])], p1 = m.vertices[static_cast<std::size_t>(t[1])],
                       p2 = m.vertices[static_cast<std::size_t>(t[2])];
            const double a = (p1 - p2).norm(), b = (p0 - p2).norm(), c = (p0 - p1).norm();
            const double circum = a * b * c / (2 * (p1 - p0).cross(p2 - p0).norm());
            worst = std::max(worst, r - std::sqrt(r * r - circum * circum));
        }
        return worst;
    };
    EXPECT_GE(s.distance.max, shift - depth(b) - 1e-9);
    EXPECT_LE(s.distance.max, shift + depth(a) + 1e-9);
    EXPECT_GT(std::abs(s.maxAt.x()), 0.99 * r);  // found on the x axis
    // Mean of |shift cos(theta)| over the sphere = shift / 2 (to first order in shift / r).
    EXPECT_NEAR(s.distance.mean, shift / 2, 0.01);
    // The refined max is never below the best sample, and exact within the tolerance: check it
    // against a dense lattice of brute-force points around where it was found.
    double dense = 0;
    for (std::size_t t = 0; t < a.triangles.size(); ++t) {
        const Tri& tri = a.triangles[t];
        const Vec3 p0 = a.vertices[static_cast<std::size_t>(tri[0])], p1 = a.vertices[static_cast<std::size_t>(tri[1])],
                   p2 = a.vertices[static_cast<std::size_t>(tri[2])];
        if ((p0 - s.maxAt).norm() > 2.0) continue;
        for (int i = 0; i <= 40; ++i)
            for (int j = 0; i + j <= 40; ++j) {
                const Vec3 p = p0 + (i / 40.0) * (p1 - p0) + (j / 40.0) * (p2 - p0);
                dense = std::max(dense, std::sqrt(closestTriangle(bvhB, p).squaredDistanceMm2));
            }
    }
    EXPECT_GE(s.distance.max, dense - 1e-4);
    EXPECT_LE(s.distance.max, dense + 1e-4 + 1e-3);
}

TEST(SurfaceDistance, SameResultsForAnyThreadCount) {
    const SurfaceMesh a = sphere(Vec3::Zero(), 5, 30), b = sphere(Vec3(0.2, 0.1, 0), 5.1, 50);
    const auto run = [&] {
        const TriangleBvh bvh = buildTriangleBvh(b);
        const DistanceSamples samples = sampleDistances(a, bvh, 0.3);
        std::vector<int> group(a.triangles.size());
        for (std::size_t t = 0; t < group.size(); ++t) group[t] = static_cast<int>(t % 3) - 1;  // -1 skipped
        const auto s = summarizeDistances(a, samples, group, 2, bvh, 1e-4);
        return std::make_pair(samples.distanceMm, std::vector<double>{s[0].distance.max, s[0].distance.mean, s[0].distance.p95,
                                                                      s[1].distance.max, s[1].maxAt.x(), s[1].distance.median});
    };
    decltype(run()) one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = run();
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = run();
    }
    EXPECT_EQ(one, two);
}

TEST(WeightedDistribution, PercentilesFollowTheCumulativeWeight) {
    const std::vector<double> v{5, 1, 3, 2, 4, 100};
    const std::vector<double> w{1, 1, 1, 1, 6, 0};  // total 10; 100 has no weight
    const Distribution d = summarizeWeighted(v, w);
    EXPECT_EQ(d.count, 6u);
    EXPECT_DOUBLE_EQ(d.totalWeight, 10);
    EXPECT_EQ(d.min, 1);
    EXPECT_EQ(d.max, 100);                  // extremes include weight-0 values
    EXPECT_EQ(d.p05, 1);                    // cumulative 1 >= 0.5
    EXPECT_EQ(d.median, 4);                 // cumulative 3 at 3, 9 at 4 >= 5
    EXPECT_EQ(d.p95, 5);                    // 9 < 9.5 <= 10
    EXPECT_DOUBLE_EQ(d.mean, (5 + 1 + 3 + 2 + 24) / 10.0);
    const auto h = weightedHistogram(v, w, 0, 10, 5);
    EXPECT_EQ(h, (std::vector<double>{1, 2, 7, 0, 0}));  // 5 falls in [4,6), 100 in the last bin with weight 0
    EXPECT_EQ(summarizeWeighted({}, {}).count, 0u);
    // The unit-weight shortcut agrees with explicit unit weights, ties and all.
    std::mt19937 rng(1);
    std::vector<double> many;
    for (int i = 0; i < 1001; ++i) many.push_back(std::floor(std::uniform_real_distribution<double>(0, 50)(rng)));
    const Distribution a = summarizeWeighted(many, std::vector<double>(many.size(), 1.0)), b = summarizeUnweighted(many);
    EXPECT_EQ(std::vector<double>({a.min, a.p05, a.median, a.p95, a.mean, a.max, a.totalWeight}),
              std::vector<double>({b.min, b.p05, b.median, b.p95, b.mean, b.max, b.totalWeight}));
}
