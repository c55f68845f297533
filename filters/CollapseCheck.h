// The tests of one edge collapse u -> v of the simplification (the conditions listed in
// SimplifyInterfaces.h), each a named step, run in a fixed order on a block's mesh (BlockMesh.h).
// Internal to the simplification.
#pragma once

#include "filters/BlockMesh.h"
#include "filters/RegionWedges.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace jawmesh::simplify {

/// Checks collapses on one block's mesh. The cheap tests (features and link condition, the moved
/// triangles' shapes and edges, wedges, the curve error) run first; the expensive ones (placing
/// the removed points within their bound, the new triangles' distance to the input surface, the
/// intersections) only when those pass. The queue (BlockSimplifier.h) ranks candidates by their
/// quadric cost, without any of these, and asks for the whole check only for the collapse it is
/// about to make; a refused vertex looks for the cheapest neighbour that passes the cheap tests.
class CollapseCheck {
public:
    /// Reads `mesh` and, with exhaustive intersection checks, queries its grid (which drops stale
    /// entries as it goes).
    explicit CollapseCheck(BlockMesh& mesh) : mesh_(mesh) {}

    /// True when the collapse u -> v keeps every condition; then `plan` says how to make it
    /// (BlockMesh::apply). On false, `plan` holds nothing of use.
    bool plan(std::int32_t u, std::int32_t v, CollapsePlan& plan);
    /// True when the collapse u -> v passes the cheap tests (a candidate worth queueing).
    bool cheapTestsPass(std::int32_t u, std::int32_t v);

private:
    bool cheapTestsPass();
    bool featuresAllow();
    bool linkCondition();
    bool onCollapsedEdge(std::int32_t t) const;
    bool isApex(std::int32_t x) const;
    bool movedTrianglesAllowed();
    bool movedTriangleAllowed(std::size_t m);
    bool triangleExists(std::int32_t a, std::int32_t b, std::int32_t c) const;
    bool shapeAllowed(const std::array<Vec3, 3>& oldP, const std::array<Vec3, 3>& newP) const;
    bool newEdgesShortEnough(std::int32_t t, std::int32_t a, std::int32_t b) const;
    bool wedgesAllowed();
    double smallestWedge(bool post);
    double edgeWedge(std::int32_t a, std::int32_t b, std::int32_t hub, bool post);
    bool curveWithinBound() const;
    bool placeRemovedPoints(CollapsePlan& plan);
    bool placePoint(std::int32_t p, int pairKey, double bound, std::int32_t from, CollapsePlan& plan) const;
    bool newTrianglesNearInput(const CollapsePlan& plan);
    /// A sample's bounds: from the fine surface (to an input vertex) and from the input
    /// triangles (the fine one less what the adaptive extraction spent there).
    struct Bounds {
        double fine, input;
        Bounds min(const Bounds& o) const { return {std::min(fine, o.fine), std::min(input, o.input)}; }
    };
    Bounds boundsOf(std::int32_t p, std::int32_t t) const;
    /// Input vertices a sample is measured from, and their positions side by side (every sample
    /// scans them all).
    struct NearVertices {
        std::vector<std::int32_t> ids;
        std::vector<Vec3> pos;
        void clear() {
            ids.clear();
            pos.clear();
        }
        void add(std::int32_t q, const std::vector<Vec3>& points) {
            ids.push_back(q);
            pos.push_back(points[std::size_t(q)]);
        }
    };
    bool sampleNearInput(const Vec3& x, std::int32_t t, const Bounds& cornerBound, const NearVertices& near,
                         double settleFineMm) const;
    void collectCollapseVertices(const CollapsePlan& plan);
    bool intersectionFree();
    void collectLocalTriangles();
    bool newTriangleIntersects(std::size_t m);
    bool meetsTriangle(std::size_t m, std::int32_t s, const Vec3* P, const Tri& newG, const BBox& box) const;
    void fillPlan(CollapsePlan& plan) const;

    BlockMesh& mesh_;
    // the collapse being checked
    std::int32_t u_ = -1, v_ = -1;
    std::vector<Spoke> spokes_;          ///< u's spokes
    const Spoke* uv_ = nullptr;          ///< the edge u-v among them
    const Spoke* other_ = nullptr;       ///< u's other curve edge (u on a junction curve)
    std::int32_t apex_[4] = {};          ///< apexes of u-v's triangles
    std::vector<std::int32_t> nbV_;      ///< v's neighbours, sorted
    std::vector<std::int32_t> moved_;    ///< u's triangles not on u-v
    std::vector<Tri> newTris_;           ///< and their corners after the collapse (local ids)
    std::vector<std::array<Vec3, 3>> newCorners_;  ///< and positions
    // scratch buffers
    std::vector<int> pairsDone_;
    std::vector<std::int32_t> localTris_;
    NearVertices ownNear_, allNear_;    ///< newTrianglesNearInput's: of one new triangle, of the collapse
    std::vector<std::int32_t> collapseIds_;
    std::vector<EdgeFanTriangle> wedgeFan_;
};

}  // namespace jawmesh::simplify
