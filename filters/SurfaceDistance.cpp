// Implements filters/SurfaceDistance.h; what it computes, its rules and its contract are documented there.
#include "filters/SurfaceDistance.h"

#include "filters/TriangleGeometry.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>

namespace jawmesh {
namespace {

constexpr int kMaxSubdivisions = 1000;  // per edge; only a triangle a thousand spacings long gets there
constexpr int kMaxRefineDepth = 24;     // 2^-24 of a triangle: far below any tolerance in mm

/// Sub-triangles per edge: enough for one sample per equilateral triangle of side `spacing` (by
/// area, so a dense input's small triangles get one sample each), and for a sliver at least one
/// per three spacings of its length.
int subdivisions(const Vec3& a, const Vec3& b, const Vec3& c, double spacingMm) {
    const double longest = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double byArea = std::ceil(std::sqrt(area / (0.4330127018922193 * spacingMm * spacingMm)));
    const double byLength = std::ceil(longest / (3.0 * spacingMm));
    return std::clamp(static_cast<int>(std::max(byArea, byLength)), 1, kMaxSubdivisions);
}

/// Calls f(point) for the n^2 sub-triangle centroids of (a, a + u, a + v), in sample order.
template <typename F>
void forEachSamplePoint(const Vec3& a, const Vec3& u, const Vec3& v, int n, F&& f) {
    const auto at = [&](int i3, int j3) { return Vec3(a + (i3 / (3.0 * n)) * u + (j3 / (3.0 * n)) * v); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
            f(at(3 * i + 1, 3 * j + 1));                  // upward sub-triangle
            if (i + j < n - 1) f(at(3 * i + 2, 3 * j + 2));  // the downward one beside it
        }
}

struct Corner {
    Vec3 p;
    double d;             // distance to `to`, mm (in refineMax, possibly an upper bound: measureUnlessBelow)
    std::int32_t closest; // nearest triangle of `to` (of that bound)
};

Corner measure(const TriangleBvh& to, const Vec3& p, std::int32_t hint) {
    const ClosestTriangle c = closestTriangle(to, p, hint);
    return {p, std::sqrt(c.squaredDistanceMm2), c.triangle};
}

/// p's distance and nearest triangle when the distance may exceed `bar`; else an upper bound of
/// it, at most `bar`, from a walk across the triangles near `hint`. The branch and bound needs
/// no more of a point that cannot raise its maximum (its bounds stay upper bounds), and the walk
/// costs a few triangle distances where a search of the tree costs tens.
Corner measureUnlessBelow(const TriangleBvh& to, const Vec3& p, std::int32_t hint, double bar) {
    const ClosestTriangle near = nearbyTriangle(to, p, hint);
    const double d = std::sqrt(near.squaredDistanceMm2);
    if (d <= bar) return {p, d, near.triangle};
    return measure(to, p, near.triangle);
}

/// The farthest any point of triangle (a, b, c) is from its nearest corner: the circumradius of an
/// acute triangle; for an obtuse one, where the perpendicular bisectors of the two shorter sides
/// meet the longest. Infinite for a degenerate triangle.
double coveringRadius(const Vec3& a, const Vec3& b, const Vec3& c) {
    // Name the corners so that C holds the largest angle (faces the longest side AB).
    std::array<Vec3, 3> p{a, b, c};
    const double la = (c - b).squaredNorm(), lb = (a - c).squaredNorm(), lc = (b - a).squaredNorm();
    if (la >= lb && la >= lc) p = {b, c, a};
    else if (lb >= la && lb >= lc) p = {c, a, b};
    const Vec3 ab = p[1] - p[0], ac = p[2] - p[0], bc = p[2] - p[1];
    const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm(), bc2 = bc.squaredNorm();
    const double twiceArea = ab.cross(ac).norm();
    if (!(twiceArea > 0)) return std::numeric_limits<double>::infinity();
    if (ac2 + bc2 >= ab2) return std::sqrt(ab2 * ac2 * bc2) / (2 * twiceArea);  // acute or right
    // |x - A| = |x - C| on AB lies |AC| / (2 cos A) from A (and from C); likewise for B.
    const double cosA = ab.dot(ac) / std::sqrt(ab2 * ac2), cosB = -ab.dot(bc) / std::sqrt(ab2 * bc2);
    return std::max(std::sqrt(ac2) / (2 * cosA), std::sqrt(bc2) / (2 * cosB));
}

/// Upper bound of the distance over triangle (a, b, c) without new queries: the smallest of the
/// Lipschitz bounds from the corners (each corner's distance plus the farthest point from it; the
/// largest corner distance plus the covering radius) and the convex bound of each corner's
/// nearest `to` triangle. Stops early, with a bound above `enough`, once a bound is at or under
/// it or a `to` triangle's corner distance already exceeds the bound found: the callers only ask
/// whether the bound is at most `enough`, and these shortcuts never change that answer.
double upperBound(const Corner* k, const TriangleBvh& to, double enough) {
    const double ab = (k[1].p - k[0].p).norm(), bc = (k[2].p - k[1].p).norm(), ca = (k[0].p - k[2].p).norm();
    double u = std::min({k[0].d + std::max(ab, ca), k[1].d + std::max(ab, bc), k[2].d + std::max(bc, ca)});
    // (1 + 1e-12): a margin over the rounding of the covering radius.
    u = std::min(u, std::max({k[0].d, k[1].d, k[2].d}) + coveringRadius(k[0].p, k[1].p, k[2].p) * (1 + 1e-12));
    if (u <= enough) return u;
    for (int i = 0; i < 3; ++i) {
        const auto& t = to.corners[static_cast<std::size_t>(to.slotOf[static_cast<std::size_t>(k[i].closest)])];
        double worst2 = 0;
        // Past u^2 (with a margin over the rounding of the square root) this triangle cannot lower u.
        for (int j = 0; j < 3 && worst2 <= u * u * (1 + 1e-12); ++j)
            worst2 = std::max(worst2, squaredDistanceToTriangle(k[j].p, t[0], t[1], t[2]));
        u = std::min(u, std::sqrt(worst2));
        if (u <= enough) return u;
    }
    return u;
}

/// Branch and bound over (a, b, c) given its measured corners; raises best (and *where) when a
/// point beats it. A corner's d may be an upper bound at most `best` (measureUnlessBelow): best
/// only grows, so such a point never raises it, and every bound made from it stays an upper bound.
/// Serial and in a fixed order, so the result depends only on the inputs.
void refineMax(const Corner& a, const Corner& b, const Corner& c, const TriangleBvh& to, double toleranceMm,
               double& best, Vec3* where) {
    struct Item {
        Corner k[3];
        int depth;
    };
    std::vector<Item> stack;
    stack.push_back({{a, b, c}, 0});
    const auto raise = [&](const Corner& k) {
        if (k.d > best) {
            best = k.d;
            if (where) *where = k.p;
        }
    };
    raise(a);
    raise(b);
    raise(c);
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        const Corner* k = item.k;
        if (upperBound(k, to, best + toleranceMm) <= best + toleranceMm) continue;
        const Vec3 centre = (k[0].p + k[1].p + k[2].p) / 3.0;
        const Corner m = measureUnlessBelow(to, centre, k[0].closest, best);
        raise(m);
        const double radius = std::sqrt(std::max({(k[0].p - centre).squaredNorm(), (k[1].p - centre).squaredNorm(),
                                                  (k[2].p - centre).squaredNorm()}));
        if (m.d + radius <= best + toleranceMm || item.depth >= kMaxRefineDepth) continue;
        const Corner ab = measureUnlessBelow(to, 0.5 * (k[0].p + k[1].p), k[0].closest, best);
        const Corner bc = measureUnlessBelow(to, 0.5 * (k[1].p + k[2].p), k[1].closest, best);
        const Corner ca = measureUnlessBelow(to, 0.5 * (k[2].p + k[0].p), k[2].closest, best);
        raise(ab);
        raise(bc);
        raise(ca);
        const int depth = item.depth + 1;
        stack.push_back({{k[0], ab, ca}, depth});
        stack.push_back({{ab, k[1], bc}, depth});
        stack.push_back({{ca, bc, k[2]}, depth});
        stack.push_back({{bc, ca, ab}, depth});
    }
}

}  // namespace

DistanceSamples sampleDistances(const SurfaceMesh& from, const TriangleBvh& to, double spacingMm, Progress& progress) {
    DistanceSamples s;
    const std::size_t nt = from.triangles.size();
    s.firstOfTriangle.assign(nt + 1, 0);
    std::vector<int> n(nt);
    for (std::size_t t = 0; t < nt; ++t) {
        const Tri& tri = from.triangles[t];
        n[t] = subdivisions(from.vertices[static_cast<std::size_t>(tri[0])], from.vertices[static_cast<std::size_t>(tri[1])],
                            from.vertices[static_cast<std::size_t>(tri[2])], spacingMm);
        s.firstOfTriangle[t + 1] = s.firstOfTriangle[t] + static_cast<std::int64_t>(n[t]) * n[t];
    }
    const std::size_t total = static_cast<std::size_t>(s.firstOfTriangle[nt]);
    s.distanceMm.resize(total);
    s.weightMm2.resize(total);
    s.sourceTriangle.resize(total);
    s.closestTriangle.resize(total);
    std::atomic<std::size_t> done{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
        progress.checkCancelled();
        std::int32_t hint = -1;  // the previous answer: a nearby triangle, only speeds the query up
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            const Tri& tri = from.triangles[t];
            const Vec3& a = from.vertices[static_cast<std::size_t>(tri[0])];
            const Vec3 u = from.vertices[static_cast<std::size_t>(tri[1])] - a;
            const Vec3 v = from.vertices[static_cast<std::size_t>(tri[2])] - a;
            const int k = n[t];
            const double weight = 0.5 * u.cross(v).norm() / (static_cast<double>(k) * k);
            std::size_t out = static_cast<std::size_t>(s.firstOfTriangle[t]);
            forEachSamplePoint(a, u, v, k, [&](const Vec3& p) {
                const ClosestTriangle c = closestTriangle(to, p, hint);
                hint = c.triangle;
                s.distanceMm[out] = std::sqrt(c.squaredDistanceMm2);
                s.weightMm2[out] = weight;
                s.sourceTriangle[out] = static_cast<std::int32_t>(t);
                s.closestTriangle[out] = c.triangle;
                ++out;
            });
        }
        progress.update(static_cast<double>(done += r.size()) / static_cast<double>(nt));
    });
    return s;
}

namespace {

/// The largest distance known of a group before any refinement, and where it is.
struct GroupBar {
    double mm = -1.0;
    Vec3 at = Vec3::Zero();
};

/// Each group's largest sample (the first in sample order) and where it is.
std::vector<GroupBar> sampleBars(const SurfaceMesh& from, const DistanceSamples& samples,
                                 const std::vector<int>& groupOfTriangle, std::size_t groupCount) {
    std::vector<GroupBar> bar(groupCount);
    std::vector<std::size_t> barSample(groupCount, 0);
    for (std::size_t t = 0; t < from.triangles.size(); ++t) {
        const int g = groupOfTriangle[t];
        if (g < 0) continue;
        for (std::int64_t i = samples.firstOfTriangle[t]; i < samples.firstOfTriangle[t + 1]; ++i)
            if (samples.distanceMm[static_cast<std::size_t>(i)] > bar[static_cast<std::size_t>(g)].mm) {
                bar[static_cast<std::size_t>(g)].mm = samples.distanceMm[static_cast<std::size_t>(i)];
                barSample[static_cast<std::size_t>(g)] = static_cast<std::size_t>(i);
            }
    }
    for (std::size_t g = 0; g < groupCount; ++g) {
        if (bar[g].mm < 0) continue;
        const std::size_t i = barSample[g];
        const std::size_t t = static_cast<std::size_t>(samples.sourceTriangle[i]);
        const Tri& tri = from.triangles[t];
        const Vec3& a = from.vertices[static_cast<std::size_t>(tri[0])];
        const Vec3 u = from.vertices[static_cast<std::size_t>(tri[1])] - a, v = from.vertices[static_cast<std::size_t>(tri[2])] - a;
        std::size_t index = static_cast<std::size_t>(samples.firstOfTriangle[t]);
        const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(samples.firstOfTriangle[t + 1] - samples.firstOfTriangle[t]))));
        forEachSamplePoint(a, u, v, n, [&](const Vec3& p) {
            if (index++ == i) bar[g].at = p;
        });
    }
    return bar;
}

/// Each group's bar: its sample bar or, when larger, its farthest corner (the first in triangle
/// order; a corner under the sample bar may hold only a bound, which never beats it).
std::vector<GroupBar> groupBars(const SurfaceMesh& from, const std::vector<int>& groupOfTriangle,
                                const std::vector<Corner>& corner, std::vector<GroupBar> bar) {
    for (std::size_t t = 0; t < from.triangles.size(); ++t) {
        const int g = groupOfTriangle[t];
        if (g < 0) continue;
        for (std::int32_t v : from.triangles[t])
            if (corner[static_cast<std::size_t>(v)].d > bar[static_cast<std::size_t>(g)].mm)
                bar[static_cast<std::size_t>(g)] = {corner[static_cast<std::size_t>(v)].d, corner[static_cast<std::size_t>(v)].p};
    }
    return bar;
}

/// Every corner of a grouped triangle measured once (a vertex is shared by about six triangles),
/// each query hinted by the nearest triangle of a sample beside it. A corner that cannot raise the
/// bars of its triangles' groups (`sampleBar`) keeps an upper bound of its distance under them
/// (measureUnlessBelow): the branch and bound needs no more. Unmeasured vertices keep d -1.
std::vector<Corner> measureCorners(const SurfaceMesh& from, const DistanceSamples& samples,
                                   const std::vector<int>& groupOfTriangle, const std::vector<GroupBar>& sampleBar,
                                   const TriangleBvh& to) {
    std::vector<Corner> corner(from.vertices.size(), Corner{Vec3::Zero(), -1.0, -1});
    std::vector<std::int32_t> hint(from.vertices.size(), -1);
    std::vector<double> bar(from.vertices.size(), std::numeric_limits<double>::infinity());
    for (std::size_t t = 0; t < from.triangles.size(); ++t)
        if (const int g = groupOfTriangle[t]; g >= 0)
            for (std::int32_t v : from.triangles[t]) {
                hint[static_cast<std::size_t>(v)] = samples.closestTriangle[static_cast<std::size_t>(samples.firstOfTriangle[t])];
                bar[static_cast<std::size_t>(v)] = std::min(bar[static_cast<std::size_t>(v)], sampleBar[static_cast<std::size_t>(g)].mm);
            }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, corner.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t v = r.begin(); v != r.end(); ++v)
            if (hint[v] >= 0) corner[v] = measureUnlessBelow(to, from.vertices[v], hint[v], bar[v]);
    });
    return corner;
}

}  // namespace

std::vector<DistanceSummary> summarizeDistances(const SurfaceMesh& from, const DistanceSamples& samples,
                                                const std::vector<int>& groupOfTriangle, int groupCount,
                                                const TriangleBvh& to, double toleranceMm, Progress& progress) {
    const std::size_t nt = from.triangles.size();
    std::vector<DistanceSummary> out(static_cast<std::size_t>(std::max(groupCount, 0)));
    std::vector<std::vector<double>> values(out.size()), weights(out.size());
    for (std::size_t t = 0; t < nt; ++t) {
        const int g = groupOfTriangle[t];
        if (g < 0) continue;
        for (std::int64_t i = samples.firstOfTriangle[t]; i < samples.firstOfTriangle[t + 1]; ++i) {
            values[static_cast<std::size_t>(g)].push_back(samples.distanceMm[static_cast<std::size_t>(i)]);
            weights[static_cast<std::size_t>(g)].push_back(samples.weightMm2[static_cast<std::size_t>(i)]);
        }
    }
    const std::vector<GroupBar> sampleBar = sampleBars(from, samples, groupOfTriangle, out.size());
    const std::vector<Corner> corner = measureCorners(from, samples, groupOfTriangle, sampleBar, to);
    // The bar a triangle must beat to be refined, and where the max is until one does.
    const std::vector<GroupBar> bar = groupBars(from, groupOfTriangle, corner, sampleBar);

    // Most triangles are settled by their own samples: every point of a sub-triangle is within its
    // centroid-to-corner radius of the sample at that centroid (distance is 1-Lipschitz), so a
    // triangle whose samples plus that radius stay below the bar cannot beat it. Only the others
    // get the branch and bound, from their measured corners.
    std::vector<double> triangleMax(nt, -1.0);
    std::vector<Vec3> triangleWhere(nt, Vec3::Zero());
    std::atomic<std::size_t> done{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 256), [&](const tbb::blocked_range<std::size_t>& r) {
        progress.checkCancelled();
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            const int g = groupOfTriangle[t];
            if (g < 0) continue;
            const double groupBar = bar[static_cast<std::size_t>(g)].mm;
            const Tri& tri = from.triangles[t];
            const Corner& a = corner[static_cast<std::size_t>(tri[0])];
            const Corner& b = corner[static_cast<std::size_t>(tri[1])];
            const Corner& c = corner[static_cast<std::size_t>(tri[2])];
            const std::int64_t first = samples.firstOfTriangle[t], count = samples.firstOfTriangle[t + 1] - first;
            const Vec3 centre = (a.p + b.p + c.p) / 3.0;
            const double radius = std::sqrt(std::max({(a.p - centre).squaredNorm(), (b.p - centre).squaredNorm(),
                                                      (c.p - centre).squaredNorm()})) /
                                  std::sqrt(static_cast<double>(count));  // sub-triangles are the triangle scaled by 1/n
            double worst = 0;
            for (std::int64_t i = first; i < first + count; ++i) worst = std::max(worst, samples.distanceMm[static_cast<std::size_t>(i)]);
            if (worst + radius <= groupBar + toleranceMm) continue;
            double best = groupBar;
            refineMax(a, b, c, to, toleranceMm, best, &triangleWhere[t]);
            if (best > groupBar) triangleMax[t] = best;
        }
        progress.update(static_cast<double>(done += r.size()) / static_cast<double>(nt));
    });

    for (std::size_t g = 0; g < out.size(); ++g) {
        DistanceSummary& s = out[g];
        s.distance = summarizeWeighted(values[g], weights[g]);
        s.areaMm2 = s.distance.totalWeight;
        if (values[g].empty()) continue;
        s.distance.max = bar[g].mm;
        s.maxAt = bar[g].at;
    }
    for (std::size_t t = 0; t < nt; ++t) {  // serial, lowest triangle first: a unique location
        const int g = groupOfTriangle[t];
        if (g < 0) continue;
        DistanceSummary& s = out[static_cast<std::size_t>(g)];
        if (triangleMax[t] > s.distance.max) {
            s.distance.max = triangleMax[t];
            s.maxAt = triangleWhere[t];
        }
    }
    return out;
}

}  // namespace jawmesh
