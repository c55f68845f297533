// Implements filters/TriangulateLoop.h; what it computes, its rules and its contract are documented there.
#include "filters/TriangulateLoop.h"

#include "filters/TriangleGeometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>

namespace jawmesh {
namespace {

using Vec2 = Eigen::Vector2d;

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) { return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x(); }

/// The loop in a 2-D frame (u, v) with u x v along the Newell normal: counter-clockwise.
std::vector<Vec2> projectLoop(const std::vector<Vec3>& loop) {
    const Vec3 n = newellNormal(loop).normalized();
    const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
    std::vector<Vec2> p;
    p.reserve(loop.size());
    for (const Vec3& x : loop) p.emplace_back(x.dot(u), x.dot(v));
    return p;
}

/// True when q lies inside or on the triangle a, b, c (counter-clockwise).
bool inClosedTriangle(const Vec2& q, const Vec2& a, const Vec2& b, const Vec2& c) {
    return cross2(a, b, q) >= 0 && cross2(b, c, q) >= 0 && cross2(c, a, q) >= 0;
}

}  // namespace

std::vector<Tri> earClipLoop(const std::vector<Vec3>& loop, const std::function<bool(int, int)>& diagonalAllowed) {
    const std::size_t n = loop.size();
    if (n < 3) return {};
    if (n == 3) return {Tri{0, 1, 2}};
    const std::vector<Vec2> p = projectLoop(loop);
    std::vector<int> ring(n);
    for (std::size_t i = 0; i < n; ++i) ring[i] = int(i);
    std::vector<Tri> tris;
    while (ring.size() > 3) {
        const std::size_t m = ring.size();
        int bestAt = -1;
        double bestCos = 2;  // cosine of the smallest angle: lower is better
        for (std::size_t k = 0; k < m; ++k) {
            const int a = ring[(k + m - 1) % m], b = ring[k], c = ring[(k + 1) % m];
            // strictly convex, relative to the polygon's size so rounding noise is not an ear
            const double area2 = cross2(p[std::size_t(a)], p[std::size_t(b)], p[std::size_t(c)]);
            if (!(area2 > 1e-12 * (p[std::size_t(c)] - p[std::size_t(a)]).squaredNorm())) continue;
            bool empty = true;
            for (const int q : ring)
                if (q != a && q != b && q != c && inClosedTriangle(p[std::size_t(q)], p[std::size_t(a)], p[std::size_t(b)], p[std::size_t(c)])) {
                    empty = false;
                    break;
                }
            if (!empty || !diagonalAllowed(a, c)) continue;
            const double cosine = smallestAngleCosine(loop[std::size_t(a)], loop[std::size_t(b)], loop[std::size_t(c)]);
            if (cosine < bestCos) {
                bestCos = cosine;
                bestAt = int(k);
            }
        }
        if (bestAt < 0) return {};
        const std::size_t k = std::size_t(bestAt);
        tris.push_back({ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]});
        ring.erase(ring.begin() + std::ptrdiff_t(k));
    }
    tris.push_back({ring[0], ring[1], ring[2]});
    return tris;
}

std::vector<Tri> centroidFan(std::size_t n) {
    std::vector<Tri> tris;
    for (std::size_t i = 0; i < n; ++i) tris.push_back({std::int32_t(i), std::int32_t((i + 1) % n), std::int32_t(n)});
    return tris;
}

Vec3 newellNormal(const std::vector<Vec3>& loop) {
    Vec3 n = Vec3::Zero();
    for (std::size_t i = 0; i < loop.size(); ++i) n += loop[i].cross(loop[(i + 1) % loop.size()]);
    return n;
}

Vec3 loopCentroid(const std::vector<Vec3>& loop) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& x : loop) c += x;
    return c / double(std::max<std::size_t>(loop.size(), 1));
}

double loopDiameterMm(const std::vector<Vec3>& loop) {
    double d2 = 0;
    for (std::size_t i = 0; i < loop.size(); ++i)
        for (std::size_t j = i + 1; j < loop.size(); ++j) d2 = std::max(d2, (loop[i] - loop[j]).squaredNorm());
    return std::sqrt(d2);
}

}  // namespace jawmesh
