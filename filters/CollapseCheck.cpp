// The tests of one edge collapse (CollapseCheck.h), in the order plan() runs them.
#include "filters/CollapseCheck.h"

#include "filters/SelfIntersections.h"
#include "filters/SeparatedByPlane.h"
#include "filters/TriangleGeometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace jawmesh::simplify {
namespace {

/// The nearest triangle seen so far to an input vertex x within a bound; a triangle within half
/// the bound settles it (the common case, tried from the vertex's own triangle on).
struct NearestTriangle {
    const Vec3& x;
    double best;  ///< squared distance of t, or the squared bound while none
    double good;  ///< squared half bound
    std::int32_t t = -1;

    /// True when triangle s (corners a, b, c) settles x.
    bool consider(std::int32_t s, const Vec3& a, const Vec3& b, const Vec3& c) {
        const double d = squaredDistanceToTriangle(x, a, b, c);
        if (d < best || (d == best && t < 0)) {
            best = d;
            t = s;
        }
        return d <= good;
    }
};

/// Exact intersection test of triangles P and Q (input ids ip, iq) behind the box and plane filters.
bool pairIntersects(const Vec3* P, const Tri& ip, const BBox& box, const Vec3* Q, const Tri& iq) {
    const BBox qb = boxOf(Q[0], Q[1], Q[2]);
    if ((qb.min.array() > box.max.array()).any() || (box.min.array() > qb.max.array()).any()) return false;
    if (separatedByPlane(P, ip, Q, iq) || separatedByPlane(Q, iq, P, ip)) return false;
    return trianglesIntersect(P, ip, Q, iq);
}

/// Where a new triangle is checked against the input: its centroid, its edge midpoints, and the
/// centroids of the halves a split of an edge at its midpoint makes (SplitCorners.h splits some,
/// and the tet stage's probes and faces then sit there), weights (1/2, 1/3, 1/6) in every order.
std::array<Vec3, 10> samplesOf(const std::array<Vec3, 3>& C) {
    std::array<Vec3, 10> s;
    s[0] = (C[0] + C[1] + C[2]) / 3.0;
    int k = 1;
    for (int i = 0; i < 3; ++i) s[std::size_t(k++)] = 0.5 * (C[std::size_t(i)] + C[std::size_t((i + 1) % 3)]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (j != i) s[std::size_t(k++)] = C[std::size_t(i)] / 2.0 + C[std::size_t(j)] / 3.0 + C[std::size_t(3 - i - j)] / 6.0;
    return s;
}

}  // namespace

bool CollapseCheck::plan(std::int32_t u, std::int32_t v, CollapsePlan& plan) {
    u_ = u;
    v_ = v;
    if (!cheapTestsPass()) return false;
    if (!placeRemovedPoints(plan)) return false;
    if (!newTrianglesNearInput(plan)) return false;
    if (!intersectionFree()) return false;
    fillPlan(plan);
    return true;
}

bool CollapseCheck::cheapTestsPass(std::int32_t u, std::int32_t v) {
    u_ = u;
    v_ = v;
    return cheapTestsPass();
}

/// Topology, the moved triangles, wedges and the curve error: no distances to the input.
bool CollapseCheck::cheapTestsPass() {
    const BlockMesh& M = mesh_;
    if (M.dead[std::size_t(u_)] || M.dead[std::size_t(v_)] || M.frozen[std::size_t(u_)] || M.frozen[std::size_t(v_)])
        return false;
    if (!M.spokes(u_, spokes_)) return false;
    return featuresAllow() && linkCondition() && movedTrianglesAllowed() && wedgesAllowed() && curveWithinBound();
}

/// A vertex inside one interface (a single fan) moves anywhere in it; one on a junction curve
/// only along the curve (other_: its other curve neighbour); corners of the curve network never.
bool CollapseCheck::featuresAllow() {
    int nFeature = 0;
    uv_ = nullptr;
    other_ = nullptr;
    for (const Spoke& s : spokes_) {
        if (s.w == v_) uv_ = &s;
        if (s.feature) ++nFeature;
    }
    if (!uv_) return false;
    if (nFeature == 0) return mesh_.singleFan(u_, spokes_);
    if (nFeature != 2 || !uv_->feature) return false;
    for (const Spoke& s : spokes_)
        if (s.feature && s.w != v_) other_ = &s;
    return true;
}

/// The common neighbours of u and v are exactly the apexes of u-v's triangles.
bool CollapseCheck::linkCondition() {
    for (int k = 0; k < uv_->n; ++k) apex_[k] = mesh_.third(uv_->tris[k], u_, v_);
    for (int i = 0; i < uv_->n; ++i)
        for (int j = i + 1; j < uv_->n; ++j)
            if (apex_[i] == apex_[j]) return false;
    nbV_.clear();
    mesh_.neighbours(v_, nbV_);
    int common = 0;
    for (const Spoke& s : spokes_)
        if (std::binary_search(nbV_.begin(), nbV_.end(), s.w)) ++common;
    return common == uv_->n;
}

/// Triangle t is one of u-v's (removed by the collapse).
bool CollapseCheck::onCollapsedEdge(std::int32_t t) const {
    return std::find(uv_->tris, uv_->tris + uv_->n, t) != uv_->tris + uv_->n;
}

bool CollapseCheck::isApex(std::int32_t x) const { return std::find(apex_, apex_ + uv_->n, x) != apex_ + uv_->n; }

/// The moved triangles and their new shapes, each one's tests before the next one's.
bool CollapseCheck::movedTrianglesAllowed() {
    moved_.clear();
    for (std::int32_t t : mesh_.vtris[std::size_t(u_)])
        if (!onCollapsedEdge(t)) moved_.push_back(t);
    newCorners_.resize(moved_.size());
    newTris_.resize(moved_.size());
    for (std::size_t m = 0; m < moved_.size(); ++m)
        if (!movedTriangleAllowed(m)) return false;
    return true;
}

/// Moved triangle m: its corners after the collapse (kept for the later tests), the edge link,
/// its shape and its new edges.
bool CollapseCheck::movedTriangleAllowed(std::size_t m) {
    const BlockMesh& M = mesh_;
    const std::int32_t t = moved_[m];
    Tri f = M.tri[std::size_t(t)];
    std::array<Vec3, 3> oldP, newP;
    for (int k = 0; k < 3; ++k) oldP[k] = M.pos[std::size_t(f[k])];
    for (int k = 0; k < 3; ++k)
        if (f[k] == u_) f[k] = v_;
    for (int k = 0; k < 3; ++k) newP[k] = M.pos[std::size_t(f[k])];
    newTris_[m] = f;
    newCorners_[m] = newP;
    // Edge link: (v, a, b) must not exist already.
    std::int32_t a = -1, b = -1;
    for (std::int32_t x : f)
        if (x != v_) (a < 0 ? a : b) = x;
    if (isApex(a) && isApex(b) && triangleExists(v_, a, b)) return false;
    return shapeAllowed(oldP, newP) && newEdgesShortEnough(t, a, b);
}

/// A live triangle of corner v also has corners a and b.
bool CollapseCheck::triangleExists(std::int32_t v, std::int32_t a, std::int32_t b) const {
    for (std::int32_t s : mesh_.vtris[std::size_t(v)]) {
        const Tri& g = mesh_.tri[std::size_t(s)];
        if (std::find(g.begin(), g.end(), a) != g.end() && std::find(g.begin(), g.end(), b) != g.end()) return true;
    }
    return false;
}

/// Not degenerate, no normal turned by more than maxNormalTurnDeg, no angle below minAngleDeg
/// unless the old triangle already had a smaller one.
bool CollapseCheck::shapeAllowed(const std::array<Vec3, 3>& oldP, const std::array<Vec3, 3>& newP) const {
    const Vec3 n0 = (oldP[1] - oldP[0]).cross(oldP[2] - oldP[0]);
    const Vec3 n1 = (newP[1] - newP[0]).cross(newP[2] - newP[0]);
    const double l0 = n0.norm(), l1 = n1.norm();
    if (l1 <= 1e-12 * (newP[1] - newP[0]).squaredNorm() || l1 == 0) return false;
    if (l0 > 0 && n0.dot(n1) < mesh_.cosTurn * l0 * l1) return false;
    const double oldCos = smallestAngleCosine(oldP[0], oldP[1], oldP[2]);
    const double newCos = smallestAngleCosine(newP[0], newP[1], newP[2]);
    if (newCos > std::max(mesh_.cosMinAngle, oldCos)) return false;
    return true;
}

/// The new edges v-a and v-b of moved triangle t within its interface's longest edge. An edge is
/// new unless x is the apex of a removed triangle of the same interface (then it was already one
/// of its edges). An apex across another interface does not count: at a junction curve the
/// collapse can hand a long tooth/PDL edge to a cap triangle (0.10 mm cap edges on the mandible).
bool CollapseCheck::newEdgesShortEnough(std::int32_t t, std::int32_t a, std::int32_t b) const {
    const BlockMesh& M = mesh_;
    const Vec3& pv = M.pos[std::size_t(v_)];
    const double maxEdge = M.rule(t).maxEdgeMm;
    for (std::int32_t x : {a, b}) {
        const double longest = std::min(maxEdge, M.plateEdge(u_, v_, x));
        bool existing = false;
        for (int k = 0; k < uv_->n && !existing; ++k)
            existing = apex_[k] == x && M.pair[std::size_t(uv_->tris[k])] == M.pair[std::size_t(t)];
        if (!existing && (M.pos[std::size_t(x)] - pv).norm() > longest) return false;
    }
    return true;
}

/// No region may come to span less than minWedgeDeg around an edge (RegionWedges.h), unless it
/// already did as little around u.
bool CollapseCheck::wedgesAllowed() {
    if (mesh_.opt.minWedgeDeg > 0) {
        const double after = smallestWedge(/*post=*/true);
        if (after < mesh_.opt.minWedgeDeg && after < smallestWedge(/*post=*/false)) return false;
    }
    return true;
}

/// Smallest region wedge over the edges of u's triangles as they are (post = false), or of the
/// moved triangles after the collapse (post = true: moved_, newTris_ filled, u-v's own triangles
/// gone).
double CollapseCheck::smallestWedge(bool post) {
    const std::int32_t centre = post ? v_ : u_;
    double smallest = 360;
    const auto& tris = post ? moved_ : mesh_.vtris[std::size_t(u_)];
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const Tri f = post ? newTris_[i] : mesh_.tri[std::size_t(tris[i])];
        for (int k = 0; k < 3; ++k) {
            const std::int32_t a = f[std::size_t(k)], b = f[std::size_t((k + 1) % 3)];
            smallest = std::min(smallest, edgeWedge(a, b, a == centre ? b : a, post));
        }
    }
    return smallest;
}

/// Smallest region wedge around the edge a-b, before or after the collapse (smallestWedge). Every
/// triangle on a-b holds `hub`, its endpoint other than the centre, whose list is up to date
/// except for the collapse being checked.
double CollapseCheck::edgeWedge(std::int32_t a, std::int32_t b, std::int32_t hub, bool post) {
    const BlockMesh& M = mesh_;
    const auto& uTris = M.vtris[std::size_t(u_)];
    wedgeFan_.clear();
    for (std::int32_t t : M.vtris[std::size_t(hub)]) {
        const auto movedAt = post ? std::find(moved_.begin(), moved_.end(), t) : moved_.end();
        if (post && movedAt == moved_.end() && std::find(uTris.begin(), uTris.end(), t) != uTris.end()) continue;
        const Tri g = movedAt != moved_.end() ? newTris_[std::size_t(movedAt - moved_.begin())] : M.tri[std::size_t(t)];
        int ia = -1, ib = -1;
        for (int j = 0; j < 3; ++j) {
            if (g[std::size_t(j)] == a) ia = j;
            if (g[std::size_t(j)] == b) ib = j;
        }
        if (ia < 0 || ib < 0) continue;
        const std::int32_t c = g[std::size_t(3 - ia - ib)];
        wedgeFan_.push_back({M.pos[std::size_t(c)], M.sides[std::size_t(t)][0], M.sides[std::size_t(t)][1], (ia + 1) % 3 == ib});
    }
    // a vertex that is not frozen has its whole star in the block, so the edge its whole fan
    const FanKind kind = M.frozen[std::size_t(a)] && M.frozen[std::size_t(b)] ? FanKind::Partial : FanKind::Whole;
    return smallestRegionWedgeDeg(M.pos[std::size_t(a)], M.pos[std::size_t(b)], wedgeFan_.data(), wedgeFan_.size(), kind);
}

/// Curve error: u and the points of u's two curve edges stay near the merged edge v-w.
bool CollapseCheck::curveWithinBound() const {
    if (!other_) return true;
    const BlockMesh& M = mesh_;
    double bound = std::numeric_limits<double>::infinity();
    for (std::int32_t t : M.vtris[std::size_t(u_)]) bound = std::min(bound, M.rule(t).errorMm);
    bound = std::min(bound, M.plateBound(M.gid[std::size_t(u_)]));
    const Vec3& pv = M.pos[std::size_t(v_)];
    const Vec3& pw = M.pos[std::size_t(other_->w)];
    const auto within = [&](std::int32_t p) {  // p: input vertex id
        return squaredDistanceToSegment(M.points[std::size_t(p)], pv, pw) <= bound * bound;
    };
    if (!within(M.gid[std::size_t(u_)])) return false;
    for (std::uint64_t key : {M.gkey(u_, v_), M.gkey(u_, other_->w)}) {
        const auto it = M.curvePts.find(key);
        if (it != M.curvePts.end())
            for (std::int32_t p : it->second)
                if (!within(p)) return false;
    }
    return true;
}

/// Surface error: every point of u's triangles (and u itself, once per interface) finds a
/// triangle of its own interface around v, after the collapse, within the interface's bound.
bool CollapseCheck::placeRemovedPoints(CollapsePlan& plan) {
    const BlockMesh& M = mesh_;
    plan.assign.clear();
    plan.dist.clear();
    pairsDone_.clear();
    const std::int32_t gu = M.gid[std::size_t(u_)];
    for (std::int32_t t : M.vtris[std::size_t(u_)]) {
        const int key = M.pair[std::size_t(t)];
        // the points are fine vertices: their distance is to the fine surface, nothing spent
        for (std::int32_t p : M.pts[std::size_t(t)])
            if (!placePoint(p, key, M.fineBoundOf(p, t), t, plan)) return false;
        if (std::find(pairsDone_.begin(), pairsDone_.end(), key) == pairsDone_.end()) {
            pairsDone_.push_back(key);
            if (!placePoint(gu, key, M.fineBoundOf(gu, t), t, plan)) return false;
        }
    }
    return true;
}

/// Input vertex p, now on triangle `from`: settled by the first triangle of its interface within
/// half the bound (its own triangle first, then the other moved ones, then v's), else taken by
/// the nearest one within the bound; false when none is.
bool CollapseCheck::placePoint(std::int32_t p, int pairKey, double bound, std::int32_t from, CollapsePlan& plan) const {
    const BlockMesh& M = mesh_;
    const double b2 = bound * bound;
    NearestTriangle nearest{M.points[std::size_t(p)], b2, 0.25 * b2};
    bool settled = false;
    const auto own = std::find(moved_.begin(), moved_.end(), from);
    if (own != moved_.end()) {
        const auto& C = newCorners_[std::size_t(own - moved_.begin())];
        settled = nearest.consider(from, C[0], C[1], C[2]);
    }
    for (std::size_t m = 0; m < moved_.size() && !settled; ++m) {
        if (M.pair[std::size_t(moved_[m])] != pairKey || moved_[m] == from) continue;
        settled = nearest.consider(moved_[m], newCorners_[m][0], newCorners_[m][1], newCorners_[m][2]);
    }
    const auto& vTris = M.vtris[std::size_t(v_)];
    for (std::size_t k = 0; k < vTris.size() && !settled; ++k) {
        const std::int32_t t = vTris[k];
        if (M.pair[std::size_t(t)] != pairKey || onCollapsedEdge(t)) continue;
        const Tri& f = M.tri[std::size_t(t)];
        settled = nearest.consider(t, M.pos[std::size_t(f[0])], M.pos[std::size_t(f[1])], M.pos[std::size_t(f[2])]);
    }
    if (nearest.t < 0) return false;
    plan.assign.emplace_back(p, nearest.t);
    plan.dist.push_back(float(std::sqrt(nearest.best)));
    return true;
}

/// The other direction of the error bound: every new triangle stays within the bound of the
/// input surface (a triangle can float over a dip whose input points all chose a neighbouring
/// triangle). Checked at samplesOf's ten points (the centroid and edge midpoints, where a flat
/// triangle over a curved surface is farthest from it, and the halves' centroids) against the
/// input triangles around the nearest of the triangle's input vertices (its corners and the
/// removed points it takes; failing that, of all the collapse's), then their neighbours': a
/// distance to part of the input surface, so never an underestimate.
bool CollapseCheck::newTrianglesNearInput(const CollapsePlan& plan) {
    const BlockMesh& M = mesh_;
    allNear_.clear();
    for (std::size_t m = 0; m < moved_.size(); ++m) {
        ownNear_.clear();
        for (std::int32_t x : newTris_[m]) ownNear_.add(M.gid[std::size_t(x)], M.points);
        for (const auto& pt : plan.assign)
            if (pt.second == moved_[m]) ownNear_.add(pt.first, M.points);
        // near the teeth when any corner or the nearest vertex is (NearTeeth.h): the tighter bound
        Bounds corner{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
        for (std::int32_t c : newTris_[m]) corner = corner.min(boundsOf(M.gid[std::size_t(c)], moved_[m]));
        // below every bound a sample could be judged by: a vertex that near settles the sample
        // without finding the nearest (a far-bone triangle takes a thousand carried vertices)
        double settleFine = corner.fine;
        for (std::int32_t q : ownNear_.ids) settleFine = std::min(settleFine, M.fineBoundOf(q, moved_[m]));
        for (const Vec3& x : samplesOf(newCorners_[m])) {
            if (sampleNearInput(x, moved_[m], corner, ownNear_, settleFine)) continue;
            if (allNear_.ids.empty()) collectCollapseVertices(plan);
            if (!sampleNearInput(x, moved_[m], corner, allNear_, 0.0)) return false;
        }
    }
    return true;
}

/// allNear_: every input vertex of the collapse (its removed points, the new triangles' corners), once each.
void CollapseCheck::collectCollapseVertices(const CollapsePlan& plan) {
    const BlockMesh& M = mesh_;
    collapseIds_.clear();
    for (const auto& pt : plan.assign) collapseIds_.push_back(pt.first);
    for (const Tri& f : newTris_)
        for (std::int32_t x : f) collapseIds_.push_back(M.gid[std::size_t(x)]);
    std::sort(collapseIds_.begin(), collapseIds_.end());
    collapseIds_.erase(std::unique(collapseIds_.begin(), collapseIds_.end()), collapseIds_.end());
    for (std::int32_t q : collapseIds_) allNear_.add(q, M.points);
}

CollapseCheck::Bounds CollapseCheck::boundsOf(std::int32_t p, std::int32_t t) const {
    return {mesh_.fineBoundOf(p, t), mesh_.boundOf(p, t)};
}

/// Sample x of new triangle t within the bound of the input surface, measured from the input
/// vertices `near` (newTrianglesNearInput). `settleFineMm` is at most the fine bound of every
/// vertex of `near` and of the corners: a vertex within it decides as the nearest one would.
bool CollapseCheck::sampleNearInput(const Vec3& x, std::int32_t t, const Bounds& cornerBound, const NearVertices& near,
                                    double settleFineMm) const {
    const BlockMesh& M = mesh_;
    const InputSurface& in = *M.state.input;
    // p: the nearest input vertex (on the fine interface); c: the nearest corner, whose input
    // triangles are searched (carried vertices have none)
    std::size_t p = 0;
    std::int32_t c = -1;
    double d2 = std::numeric_limits<double>::infinity(), c2 = d2;
    const double settle2 = settleFineMm * settleFineMm;
    for (std::size_t i = 0; i < near.pos.size(); ++i) {
        const double e = (near.pos[i] - x).squaredNorm();
        if (e <= settle2) return true;
        if (e < d2) {
            d2 = e;
            p = i;
        }
        if (e < c2 && in.around.count(near.ids[i]) > 0) {
            c2 = e;
            c = near.ids[i];
        }
    }
    const Bounds bound = boundsOf(near.ids[p], t).min(cornerBound);
    // an input vertex is a fine vertex, on the fine surface: its distance spends nothing
    if (d2 <= bound.fine * bound.fine) return true;
    const double b2 = bound.input * bound.input;
    const auto within = [&](std::int32_t s) {
        const Tri& f = (*in.tris)[std::size_t(s)];
        return squaredDistanceToTriangle(x, M.points[std::size_t(f[0])], M.points[std::size_t(f[1])],
                                         M.points[std::size_t(f[2])]) <= b2;
    };
    if (in.anyAround(c, within)) return true;
    return in.anyAround(c, [&](std::int32_t s) {
        for (std::int32_t q : (*in.tris)[std::size_t(s)])
            if (q != c && in.anyAround(q, within)) return true;
        return false;
    });
}

/// Intersections: every new triangle against everything its box meets (exhaustive), or against
/// the triangles around u's and v's neighbours (local: folds and junctions; the output check
/// catches the rest and triggers an exhaustive rerun).
bool CollapseCheck::intersectionFree() {
    if (!mesh_.opt.exhaustiveIntersectionChecks) collectLocalTriangles();
    for (std::size_t m = 0; m < moved_.size(); ++m)
        if (newTriangleIntersects(m)) return false;
    return true;
}

/// The triangles around v's and u's neighbours, sorted, once each.
void CollapseCheck::collectLocalTriangles() {
    localTris_.clear();
    for (std::int32_t w : nbV_)
        for (std::int32_t t : mesh_.vtris[std::size_t(w)]) localTris_.push_back(t);
    for (const Spoke& s : spokes_)
        for (std::int32_t t : mesh_.vtris[std::size_t(s.w)]) localTris_.push_back(t);
    std::sort(localTris_.begin(), localTris_.end());
    localTris_.erase(std::unique(localTris_.begin(), localTris_.end()), localTris_.end());
}

/// New triangle m meets another triangle of the block after the collapse, or an obstacle.
bool CollapseCheck::newTriangleIntersects(std::size_t m) {
    const Vec3* P = newCorners_[m].data();
    const Tri newG = mesh_.global(newTris_[m]);
    const BBox box = boxOf(P[0], P[1], P[2]);
    bool hit = false;
    const auto visit = [&](std::int32_t s) {
        if (hit || s == moved_[m]) return;
        hit = meetsTriangle(m, s, P, newG, box);
    };
    if (mesh_.opt.exhaustiveIntersectionChecks) mesh_.grid.query(box, visit);
    else
        for (std::int32_t t : localTris_) visit(t);
    return hit;
}

/// New triangle m (corners P, input ids newG, box) meets triangle s as it is after the collapse
/// (s >= the block's triangle count: obstacle s - that count).
bool CollapseCheck::meetsTriangle(std::size_t m, std::int32_t s, const Vec3* P, const Tri& newG, const BBox& box) const {
    const BlockMesh& M = mesh_;
    Vec3 Q[3];
    Tri g;
    if (std::size_t(s) >= M.tri.size()) {  // another block's triangle
        g = M.obstacles[std::size_t(s) - M.tri.size()];
        for (int i = 0; i < 3; ++i) Q[i] = M.points[std::size_t(g[std::size_t(i)])];
        return pairIntersects(P, newG, box, Q, g);
    }
    if (!M.alive[std::size_t(s)] || onCollapsedEdge(s)) return false;
    const auto mi = std::find(moved_.begin(), moved_.end(), s);
    if (mi != moved_.end()) {
        const std::size_t k = std::size_t(mi - moved_.begin());
        if (k < m) return false;  // pair already tested from the other side
        g = newTris_[k];
        for (int i = 0; i < 3; ++i) Q[i] = newCorners_[k][std::size_t(i)];
    } else {
        g = M.tri[std::size_t(s)];
        for (int i = 0; i < 3; ++i) Q[i] = M.pos[std::size_t(g[std::size_t(i)])];
    }
    return pairIntersects(P, newG, box, Q, M.global(g));
}

void CollapseCheck::fillPlan(CollapsePlan& plan) const {
    const BlockMesh& M = mesh_;
    plan.removed.assign(uv_->tris, uv_->tris + uv_->n);
    plan.moved = moved_;
    plan.curveOther = other_ ? other_->w : -1;
    plan.curvePoints.clear();
    if (other_) {
        plan.curvePoints.push_back(M.gid[std::size_t(u_)]);
        for (std::uint64_t key : {M.gkey(u_, v_), M.gkey(u_, other_->w), M.gkey(v_, other_->w)}) {
            const auto it = M.curvePts.find(key);
            if (it != M.curvePts.end()) plan.curvePoints.insert(plan.curvePoints.end(), it->second.begin(), it->second.end());
        }
    }
}

}  // namespace jawmesh::simplify
