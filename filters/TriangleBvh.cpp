// Implements filters/TriangleBvh.h; what it computes, its rules and its contract are documented there.
#include "filters/TriangleBvh.h"

#include "filters/TriangleGeometry.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <map>
#include <numeric>

namespace jawmesh {
namespace {

constexpr std::int32_t kLeafSize = 4;

/// Leaves of the subtree over n triangles (median splits until <= kLeafSize), memoised: the sizes
/// at one depth differ by at most one, so there are about 2 log n distinct sizes.
std::int64_t leafCount(std::int64_t n, std::map<std::int64_t, std::int64_t>& memo) {
    if (n <= kLeafSize) return 1;
    auto it = memo.find(n);
    if (it != memo.end()) return it->second;
    const std::int64_t leaves = leafCount(n / 2, memo) + leafCount(n - n / 2, memo);
    memo[n] = leaves;
    return leaves;
}

struct Builder {
    const std::vector<Vec3>& vertices;
    const std::vector<Tri>& triangles;
    const std::vector<Vec3>& centroids;
    const std::map<std::int64_t, std::int64_t>& leaves;  // complete for every subtree size
    std::vector<std::int32_t>& order;                    // triangle indices, permuted into leaf order
    TriangleBvh& bvh;

    std::int64_t nodeCount(std::int64_t n) const { return n <= kLeafSize ? 1 : 2 * leaves.at(n) - 1; }

    // Subtree over order[begin, end) into nodes starting at `node`; disjoint ranges, so subtrees
    // build in parallel and the layout never depends on scheduling.
    void build(std::int64_t begin, std::int64_t end, std::int64_t node) {
        const std::int64_t n = end - begin;
        TriangleBvh::Node& out = bvh.nodes[static_cast<std::size_t>(node)];
        if (n <= kLeafSize) {
            Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
            for (std::int64_t i = begin; i < end; ++i) {
                const Tri& t = triangles[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
                for (int k = 0; k < 3; ++k) {
                    const Vec3& v = vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
                    lo = lo.cwiseMin(v);
                    hi = hi.cwiseMax(v);
                }
            }
            out.lo = {lo.x(), lo.y(), lo.z()};
            out.hi = {hi.x(), hi.y(), hi.z()};
            out.first = static_cast<std::int32_t>(begin);
            out.count = static_cast<std::int32_t>(n);
            return;
        }
        // Split at the median centroid along the widest spread of the centroids.
        Vec3 clo = Vec3::Constant(std::numeric_limits<double>::infinity()), chi = -clo;
        for (std::int64_t i = begin; i < end; ++i) {
            const Vec3& c = centroids[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])];
            clo = clo.cwiseMin(c);
            chi = chi.cwiseMax(c);
        }
        int axis = 0;
        (chi - clo).maxCoeff(&axis);
        const std::int64_t mid = begin + n / 2;
        std::nth_element(order.data() + begin, order.data() + mid, order.data() + end, [&](std::int32_t a, std::int32_t b) {
            const double ca = centroids[static_cast<std::size_t>(a)][axis], cb = centroids[static_cast<std::size_t>(b)][axis];
            return ca < cb || (ca == cb && a < b);
        });
        const std::int64_t left = node + 1, right = node + 1 + nodeCount(mid - begin);
        out.right = static_cast<std::int32_t>(right);
        if (n > 20000) {
            tbb::parallel_invoke([&] { build(begin, mid, left); }, [&] { build(mid, end, right); });
        } else {
            build(begin, mid, left);
            build(mid, end, right);
        }
        // The box from the children's, so every triangle is looked at once (at its leaf).
        const TriangleBvh::Node& l = bvh.nodes[static_cast<std::size_t>(left)];
        const TriangleBvh::Node& r = bvh.nodes[static_cast<std::size_t>(right)];
        for (std::size_t k = 0; k < 3; ++k) {
            out.lo[k] = std::min(l.lo[k], r.lo[k]);
            out.hi[k] = std::max(l.hi[k], r.hi[k]);
        }
    }
};

inline double boxSquaredDistance(const TriangleBvh::Node& node, const Vec3& p) {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) {
        const double below = node.lo[static_cast<std::size_t>(k)] - p[k];
        const double above = p[k] - node.hi[static_cast<std::size_t>(k)];
        const double d = std::max({below, above, 0.0});
        d2 += d * d;
    }
    return d2;
}

/// bvh.edgeNeighbour from the triangles' vertex indices: each vertex's slots, then per edge the
/// lowest other slot around its first vertex that also holds its second.
void linkEdgeNeighbours(const std::vector<Vec3>& vertices, const std::vector<Tri>& triangles, TriangleBvh& bvh) {
    const std::size_t n = bvh.triangle.size();
    std::vector<std::int32_t> first(vertices.size() + 1, 0), slots(3 * n);
    for (const Tri& t : triangles)
        for (std::int32_t v : t) ++first[static_cast<std::size_t>(v) + 1];
    std::partial_sum(first.begin(), first.end(), first.begin());
    std::vector<std::int32_t> fill(first.begin(), first.end() - 1);
    for (std::size_t s = 0; s < n; ++s)  // slots ascending within each vertex's list
        for (std::int32_t v : triangles[static_cast<std::size_t>(bvh.triangle[s])])
            slots[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = static_cast<std::int32_t>(s);
    bvh.edgeNeighbour.assign(n, {-1, -1, -1});
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t s = r.begin(); s != r.end(); ++s) {
            const Tri& t = triangles[static_cast<std::size_t>(bvh.triangle[s])];
            for (std::size_t k = 0; k < 3; ++k) {
                const std::int32_t a = t[k], b = t[(k + 1) % 3];
                if (a == b) continue;
                for (std::int32_t i = first[static_cast<std::size_t>(a)]; i < first[static_cast<std::size_t>(a) + 1]; ++i) {
                    const std::int32_t o = slots[static_cast<std::size_t>(i)];
                    const Tri& u = triangles[static_cast<std::size_t>(bvh.triangle[static_cast<std::size_t>(o)])];
                    if (o != static_cast<std::int32_t>(s) && (u[0] == b || u[1] == b || u[2] == b)) {
                        bvh.edgeNeighbour[s][k] = o;
                        break;
                    }
                }
            }
        }
    });
}

}  // namespace

TriangleBvh buildTriangleBvh(const std::vector<Vec3>& vertices, const std::vector<Tri>& triangles) {
    TriangleBvh bvh;
    const std::int64_t n = static_cast<std::int64_t>(triangles.size());
    if (n == 0) return bvh;
    std::vector<Vec3> centroids(triangles.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const Tri& t = triangles[i];
            centroids[i] = (vertices[static_cast<std::size_t>(t[0])] + vertices[static_cast<std::size_t>(t[1])] +
                            vertices[static_cast<std::size_t>(t[2])]) / 3.0;
        }
    });
    std::map<std::int64_t, std::int64_t> leaves;
    const std::int64_t totalLeaves = leafCount(n, leaves);
    bvh.nodes.resize(static_cast<std::size_t>(2 * totalLeaves - 1));
    std::vector<std::int32_t> order(triangles.size());
    std::iota(order.begin(), order.end(), 0);
    Builder{vertices, triangles, centroids, leaves, order, bvh}.build(0, n, 0);

    bvh.corners.resize(triangles.size());
    bvh.triangle = order;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const Tri& t = triangles[static_cast<std::size_t>(order[i])];
            for (std::size_t k = 0; k < 3; ++k) bvh.corners[i][k] = vertices[static_cast<std::size_t>(t[k])];
        }
    });
    bvh.slotOf.resize(triangles.size());
    for (std::size_t i = 0; i < order.size(); ++i) bvh.slotOf[static_cast<std::size_t>(order[i])] = static_cast<std::int32_t>(i);
    linkEdgeNeighbours(vertices, triangles, bvh);
    return bvh;
}

ClosestTriangle closestTriangle(const TriangleBvh& bvh, const Vec3& p, std::int32_t hintTriangle) {
    ClosestTriangle best;
    if (bvh.empty()) return best;
    const auto consider = [&](std::size_t slot) {
        const auto& c = bvh.corners[slot];
        const double d2 = squaredDistanceToTriangle(p, c[0], c[1], c[2]);
        const std::int32_t tri = bvh.triangle[slot];
        if (d2 < best.squaredDistanceMm2 || (d2 == best.squaredDistanceMm2 && tri < best.triangle)) {
            best.squaredDistanceMm2 = d2;
            best.triangle = tri;
        }
    };
    if (hintTriangle >= 0 && static_cast<std::size_t>(hintTriangle) < bvh.slotOf.size())
        consider(static_cast<std::size_t>(bvh.slotOf[static_cast<std::size_t>(hintTriangle)]));

    // Depth is about log2(n / 4) + 1; 64 entries cover any tree that fits in memory.
    std::int32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const TriangleBvh::Node& node = bvh.nodes[static_cast<std::size_t>(stack[--top])];
        // '>' keeps boxes at exactly the best distance: they may hold a tie with a lower index.
        if (boxSquaredDistance(node, p) > best.squaredDistanceMm2) continue;
        if (node.count > 0) {
            for (std::int32_t s = node.first; s < node.first + node.count; ++s) consider(static_cast<std::size_t>(s));
            continue;
        }
        const std::int32_t left = static_cast<std::int32_t>(&node - bvh.nodes.data()) + 1, right = node.right;
        const double dl = boxSquaredDistance(bvh.nodes[static_cast<std::size_t>(left)], p);
        const double dr = boxSquaredDistance(bvh.nodes[static_cast<std::size_t>(right)], p);
        if (dl <= dr) {
            if (dr <= best.squaredDistanceMm2) stack[top++] = right;
            if (dl <= best.squaredDistanceMm2) stack[top++] = left;
        } else {
            if (dl <= best.squaredDistanceMm2) stack[top++] = left;
            if (dr <= best.squaredDistanceMm2) stack[top++] = right;
        }
    }
    return best;
}

ClosestTriangle nearbyTriangle(const TriangleBvh& bvh, const Vec3& p, std::int32_t fromTriangle, int maxSteps) {
    if (bvh.empty() || fromTriangle < 0 || static_cast<std::size_t>(fromTriangle) >= bvh.slotOf.size()) return {};
    const auto distance2 = [&](std::int32_t slot) {
        const auto& c = bvh.corners[static_cast<std::size_t>(slot)];
        return squaredDistanceToTriangle(p, c[0], c[1], c[2]);
    };
    std::int32_t slot = bvh.slotOf[static_cast<std::size_t>(fromTriangle)];
    double d2 = distance2(slot);
    for (int step = 0; step < maxSteps; ++step) {
        std::int32_t next = -1;
        for (std::int32_t o : bvh.edgeNeighbour[static_cast<std::size_t>(slot)]) {
            if (o < 0) continue;
            const double e2 = distance2(o);
            if (e2 < d2) {
                d2 = e2;
                next = o;
            }
        }
        if (next < 0) break;
        slot = next;
    }
    return {d2, bvh.triangle[static_cast<std::size_t>(slot)]};
}

}  // namespace jawmesh
