// The simplification of SimplifyInterfaces.h: the serial edge-collapse simplifier of one block,
// the block partition and its passes, and simplifyInterfaces with its checks and statistics.
#include "filters/SimplifyInterfaces.h"

#include "filters/NearTeeth.h"
#include "filters/PlateThickness.h"
#include "filters/RegionWedges.h"
#include "io/Angles.h"
#include "io/ResourceUsage.h"

#include "filters/SelfIntersections.h"
#include "filters/SeparatedByPlane.h"
#include "filters/SimplifyState.h"
#include "filters/SplitCorners.h"
#include "filters/ShellSeeds.h"
#include "filters/TriangleBoxGrid.h"
#include "filters/TriangleGeometry.h"
#include "io/Error.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <queue>
#include <unordered_map>

namespace jawmesh {
namespace {

using simplify::Block;
using simplify::BlockResult;
using simplify::InputSurface;
using simplify::PairRule;
using simplify::State;

/// Serial simplification of one block. Vertices on the block border (with triangles in other
/// blocks) are frozen: they neither move nor take a collapse (their star is incomplete here).
/// Writes err and quadrics of the block's own vertices straight into `state` (no other block
/// touches them); everything else comes back in the BlockResult.
class Simplifier {
public:
    Simplifier(State& state, const Block& block, const std::vector<char>& border, const SimplifyOptions& o)
        : opt_(o), state_(state), points_(*state.points), grid_(cellSize(state, block)) {
        std::unordered_map<std::int32_t, std::int32_t> local;
        local.reserve(block.tris.size());
        const auto localOf = [&](std::int32_t g) {
            const auto [it, fresh] = local.emplace(g, std::int32_t(gid_.size()));
            if (fresh) gid_.push_back(g);
            return it->second;
        };
        const std::size_t nt = block.tris.size();
        tri_.resize(nt);
        sides_.resize(nt);
        pts_.resize(nt);
        for (std::size_t t = 0; t < nt; ++t) {
            const std::size_t g = std::size_t(block.tris[t]);
            for (int k = 0; k < 3; ++k) tri_[t][k] = localOf(state.tris[g][k]);
            sides_[t] = state.sides[g];
            pts_[t] = state.pts[g];
        }
        const std::size_t nv = gid_.size();
        pos_.resize(nv);
        q_.resize(nv);
        frozen_.resize(nv);
        for (std::size_t l = 0; l < nv; ++l) {
            pos_[l] = points_[std::size_t(gid_[l])];
            q_[l] = state.quadrics[std::size_t(gid_[l])];
            frozen_[l] = border[std::size_t(gid_[l])];
        }
        pair_.resize(nt);
        alive_.assign(nt, 1);
        vtris_.resize(nv);
        stamp_.assign(nv, 0);
        dead_.assign(nv, 0);
        cosTurn_ = std::cos(o.maxNormalTurnDeg * kPi / 180.0);
        cosMinAngle_ = std::cos(o.minAngleDeg * kPi / 180.0);
        for (std::size_t t = 0; t < nt; ++t) {
            const Tri& f = tri_[t];
            for (int k = 0; k < 3; ++k) vtris_[std::size_t(f[k])].push_back(std::int32_t(t));
            pair_[t] = interfaceMarker(sides_[t][0], sides_[t][1]);
            rules_.try_emplace(pair_[t], ruleFor(sides_[t][0], sides_[t][1]));
            if (o.exhaustiveIntersectionChecks) grid_.place(std::int32_t(t), boxOf(pos_[f[0]], pos_[f[1]], pos_[f[2]]));
            // the curve edges this block owns: those with an endpoint that may move
            for (int k = 0; k < 3; ++k) {
                const std::int32_t a = f[k], b = f[(k + 1) % 3];
                if (frozen_[std::size_t(a)] && frozen_[std::size_t(b)]) continue;
                const std::uint64_t key = edgeKey(gid_[std::size_t(a)], gid_[std::size_t(b)]);
                const auto it = state.curvePts.find(key);
                if (it != state.curvePts.end() && !curvePts_.count(key)) {
                    curvePts_.emplace(key, it->second);
                    taken_.push_back(key);
                }
            }
        }
        obstacles_.reserve(block.obstacles.size());
        for (std::int32_t g : o.exhaustiveIntersectionChecks ? block.obstacles : std::vector<std::int32_t>{}) {
            const Tri& f = state.tris[std::size_t(g)];
            obstacles_.push_back(f);
            grid_.place(std::int32_t(nt + obstacles_.size() - 1),
                        boxOf(points_[std::size_t(f[0])], points_[std::size_t(f[1])], points_[std::size_t(f[2])]));
        }
    }

    /// Cell of the intersection grid: a few of the block's shortest edges.
    static double cellSize(const State& st, const Block& b) {
        double e = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < std::min<std::size_t>(b.tris.size(), 512); ++i) {
            const Tri& f = st.tris[std::size_t(b.tris[i])];
            e = std::min(e, ((*st.points)[std::size_t(f[0])] - (*st.points)[std::size_t(f[1])]).norm());
        }
        return std::isfinite(e) && e > 0 ? 6.0 * std::max(e, 1e-3) : 0.3;
    }

    void run(Progress& progress) {
        const std::size_t nv = pos_.size();
        for (std::size_t u = 0; u < nv; ++u) schedule(std::int32_t(u));
        std::size_t popped = 0;
        while (!heap_.empty()) {
            const Candidate c = heap_.top();
            heap_.pop();
            if (++popped % 65536 == 0) progress.checkCancelled();
            if (dead_[std::size_t(c.u)] || stamp_[std::size_t(c.u)] != c.stamp) continue;
            if (!evaluate(c.u, c.v, &plan_)) {
                schedule(c.u, true, c.v);  // terminates: unchanged state gives the same verdict
                continue;
            }
            apply(c.u, c.v, plan_);
            ++collapses_;
            // Everything whose neighbourhood changed gets a fresh candidate.
            ring_.clear();
            neighbours(c.v, ring_);
            const std::vector<std::int32_t> ring = ring_;
            schedule(c.v);
            for (std::int32_t w : ring) schedule(w);
        }
    }

    /// The block's triangles in input vertex ids; also writes its vertices' quadrics back.
    BlockResult result() {
        BlockResult r;
        for (std::size_t t = 0; t < tri_.size(); ++t) {
            if (!alive_[t]) continue;
            Tri f = tri_[t];
            for (auto& v : f) v = gid_[std::size_t(v)];
            r.tris.push_back(f);
            r.sides.push_back(sides_[t]);
            r.pts.push_back(std::move(pts_[t]));
        }
        for (std::size_t l = 0; l < gid_.size(); ++l)
            if (!frozen_[l]) state_.quadrics[std::size_t(gid_[l])] = q_[l];
        r.takenCurves = std::move(taken_);
        r.curves = std::move(curvePts_);
        r.collapses = collapses_;
        return r;
    }

private:
    struct Candidate {
        double cost;
        std::int32_t u, v;
        std::uint32_t stamp;
        bool operator<(const Candidate& o) const {  // priority_queue pops the largest: invert
            if (cost != o.cost) return cost > o.cost;
            if (u != o.u) return u > o.u;
            return v > o.v;
        }
    };

    /// One edge u-w seen from u: its triangles (up to a few).
    struct Spoke {
        std::int32_t w;
        std::int32_t tris[4];
        int n = 0;
        bool feature = false;
    };

    /// What evaluate() decided, used by apply() right after.
    struct Plan {
        std::vector<std::int32_t> removed, moved;   // triangles on u-v / the rest of u's fan
        std::int32_t curveOther = -1;               // u's other curve neighbour (curve vertex)
        std::vector<std::pair<std::int32_t, std::int32_t>> assign;  // input vertex -> triangle
        std::vector<float> dist;                    // its distance
        std::vector<std::int32_t> curvePoints;      // points of the merged curve edge v-w
    };

    static BBox boxOf(const Vec3& a, const Vec3& b, const Vec3& c) {
        BBox box;
        box.extend(a);
        box.extend(b);
        box.extend(c);
        return box;
    }

    PairRule ruleFor(Label a, Label b) const {
        const InterfaceBounds bounds = boundsOf(opt_);
        return {bounds.boundMm(a, b, true), bounds.maxEdgeMm(a, b), bounds.boundMm(a, b, false)};
    }

    std::uint64_t gkey(std::int32_t a, std::int32_t b) const { return edgeKey(gid_[std::size_t(a)], gid_[std::size_t(b)]); }
    Tri global(Tri f) const {
        for (auto& v : f) v = gid_[std::size_t(v)];
        return f;
    }

    const PairRule& rule(std::int32_t t) const { return rules_.at(pair_[std::size_t(t)]); }
    /// The error bound of input vertex p on triangle t's interface.
    double boundOf(std::int32_t p, std::int32_t t) const {
        const PairRule& r = rule(t);
        const auto& S = *state_.spentMm;
        const double spent = std::size_t(p) < S.size() ? double(S[std::size_t(p)]) : 0.0;
        return std::max(0.0, std::min(state_.nearTeeth[std::size_t(p)] ? r.errorMm : r.farErrorMm, plateBound(p)) - spent);
    }
    /// How far a thin plate's sheet may move at input vertex p (infinite off plates).
    double plateBound(std::int32_t p) const {
        return opt_.plateErrorFraction * double((*state_.plateMm)[std::size_t(p)]);
    }
    /// Longest new edge on a thin plate at local vertices a, b, c (infinite off plates).
    double plateEdge(std::int32_t a, std::int32_t b, std::int32_t c) const {
        const auto& T = *state_.plateMm;
        return opt_.plateEdgeFactor * double(std::min({T[std::size_t(gid_[std::size_t(a)])], T[std::size_t(gid_[std::size_t(b)])],
                                                       T[std::size_t(gid_[std::size_t(c)])]}));
    }

    std::int32_t third(std::int32_t t, std::int32_t a, std::int32_t b) const {
        for (std::int32_t x : tri_[std::size_t(t)])
            if (x != a && x != b) return x;
        return -1;
    }

    void neighbours(std::int32_t u, std::vector<std::int32_t>& out) const {
        for (std::int32_t t : vtris_[std::size_t(u)])
            for (std::int32_t x : tri_[std::size_t(t)])
                if (x != u) out.push_back(x);
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
    }

    /// The spokes of u, sorted by neighbour id; false when an edge has more than 4 triangles.
    bool spokes(std::int32_t u, std::vector<Spoke>& out) const {
        out.clear();
        for (std::int32_t t : vtris_[std::size_t(u)])
            for (std::int32_t x : tri_[std::size_t(t)]) {
                if (x == u) continue;
                auto it = std::find_if(out.begin(), out.end(), [&](const Spoke& s) { return s.w == x; });
                if (it == out.end()) {
                    out.push_back(Spoke{x, {}, 0, false});
                    it = out.end() - 1;
                }
                if (it->n == 4) return false;
                it->tris[it->n++] = t;
            }
        for (Spoke& s : out) {
            s.feature = s.n != 2;
            for (int k = 1; k < s.n; ++k)
                if (pair_[std::size_t(s.tris[k])] != pair_[std::size_t(s.tris[0])]) s.feature = true;
        }
        std::sort(out.begin(), out.end(), [](const Spoke& a, const Spoke& b) { return a.w < b.w; });
        return true;
    }

    /// For a vertex without feature edges: true when its triangles form one fan (a disc).
    bool singleFan(std::int32_t u, const std::vector<Spoke>& sp) const {
        const auto& T = vtris_[std::size_t(u)];
        if (T.size() != sp.size() || T.size() < 3) return false;
        std::int32_t t = T[0];
        std::int32_t w = third(t, u, tri_[std::size_t(t)][0] == u ? tri_[std::size_t(t)][1] : tri_[std::size_t(t)][0]);
        std::size_t steps = 0;
        do {
            const auto it = std::lower_bound(sp.begin(), sp.end(), w, [](const Spoke& s, std::int32_t x) { return s.w < x; });
            if (it == sp.end() || it->w != w || it->n != 2) return false;
            const std::int32_t next = it->tris[0] == t ? it->tris[1] : it->tris[0];
            w = third(next, u, w);
            t = next;
            ++steps;
        } while (t != T[0] && steps <= T.size());
        return steps == T.size();
    }

    /// Checks every condition of the file comment for u -> v; fills plan when given.
    /// The two expensive tests (the removed points' error and intersections) run only when a plan
    /// is asked for (the collapse is about to be made); schedule() ranks candidates without them.
    bool evaluate(std::int32_t u, std::int32_t v, Plan* plan) {
        if (dead_[std::size_t(u)] || dead_[std::size_t(v)] || frozen_[std::size_t(u)] || frozen_[std::size_t(v)])
            return false;
        std::vector<Spoke>& sp = spokeBuf_;
        if (!spokes(u, sp)) return false;
        int nFeature = 0;
        const Spoke* uv = nullptr;
        const Spoke* other = nullptr;
        for (const Spoke& s : sp) {
            if (s.w == v) uv = &s;
            if (s.feature) ++nFeature;
        }
        if (!uv) return false;
        if (nFeature == 0) {
            if (!singleFan(u, sp)) return false;
        } else if (nFeature == 2) {
            if (!uv->feature) return false;
            for (const Spoke& s : sp)
                if (s.feature && s.w != v) other = &s;
        } else {
            return false;  // corner of the curve network
        }

        // Link condition: the common neighbours of u and v are exactly the apexes of u-v's triangles.
        std::int32_t apex[4];
        for (int k = 0; k < uv->n; ++k) apex[k] = third(uv->tris[k], u, v);
        for (int i = 0; i < uv->n; ++i)
            for (int j = i + 1; j < uv->n; ++j)
                if (apex[i] == apex[j]) return false;
        nbV_.clear();
        neighbours(v, nbV_);
        int common = 0;
        for (const Spoke& s : sp)
            if (std::binary_search(nbV_.begin(), nbV_.end(), s.w)) ++common;
        if (common != uv->n) return false;
        const auto isApex = [&](std::int32_t x) { return std::find(apex, apex + uv->n, x) != apex + uv->n; };

        // The moved triangles and their new shapes.
        moved_.clear();
        for (std::int32_t t : vtris_[std::size_t(u)])
            if (std::find(uv->tris, uv->tris + uv->n, t) == uv->tris + uv->n) moved_.push_back(t);
        const Vec3& pv = pos_[std::size_t(v)];
        newCorners_.resize(moved_.size());
        newTris_.resize(moved_.size());
        for (std::size_t m = 0; m < moved_.size(); ++m) {
            const std::int32_t t = moved_[m];
            Tri f = tri_[std::size_t(t)];
            std::array<Vec3, 3> oldP, newP;
            for (int k = 0; k < 3; ++k) oldP[k] = pos_[std::size_t(f[k])];
            for (int k = 0; k < 3; ++k)
                if (f[k] == u) f[k] = v;
            for (int k = 0; k < 3; ++k) newP[k] = pos_[std::size_t(f[k])];
            newTris_[m] = f;
            newCorners_[m] = newP;
            // Edge link: (v, a, b) must not exist already.
            std::int32_t a = -1, b = -1;
            for (std::int32_t x : f)
                if (x != v) (a < 0 ? a : b) = x;
            if (isApex(a) && isApex(b))
                for (std::int32_t s : vtris_[std::size_t(v)]) {
                    const Tri& g = tri_[std::size_t(s)];
                    if (std::find(g.begin(), g.end(), a) != g.end() && std::find(g.begin(), g.end(), b) != g.end())
                        return false;
                }
            const Vec3 n0 = (oldP[1] - oldP[0]).cross(oldP[2] - oldP[0]);
            const Vec3 n1 = (newP[1] - newP[0]).cross(newP[2] - newP[0]);
            const double l0 = n0.norm(), l1 = n1.norm();
            if (l1 <= 1e-12 * (newP[1] - newP[0]).squaredNorm() || l1 == 0) return false;
            if (l0 > 0 && n0.dot(n1) < cosTurn_ * l0 * l1) return false;
            const double oldCos = smallestAngleCosine(oldP[0], oldP[1], oldP[2]);
            const double newCos = smallestAngleCosine(newP[0], newP[1], newP[2]);
            if (newCos > std::max(cosMinAngle_, oldCos)) return false;
            // A new edge of this triangle's interface: v-x, unless x is the apex of a removed
            // triangle of the same interface (then the edge was already one of its edges). An
            // apex across another interface does not count: at a junction curve the collapse
            // can hand a long tooth/PDL edge to a cap triangle (0.10 mm cap edges on the mandible).
            const double maxEdge = rule(t).maxEdgeMm;
            for (std::int32_t x : {a, b}) {
                const double longest = std::min(maxEdge, plateEdge(u, v, x));
                bool existing = false;
                for (int k = 0; k < uv->n && !existing; ++k)
                    existing = apex[k] == x && pair_[std::size_t(uv->tris[k])] == pair_[std::size_t(t)];
                if (!existing && (pos_[std::size_t(x)] - pv).norm() > longest) return false;
            }
        }

        // Wedges: no region may come to span less than minWedgeDeg around an edge (RegionWedges.h),
        // unless it already did as little around u.
        if (opt_.minWedgeDeg > 0) {
            const double after = smallestWedge(u, v, /*post=*/true);
            if (after < opt_.minWedgeDeg && after < smallestWedge(u, v, /*post=*/false)) return false;
        }

        // Curve error: u and the points of u's two curve edges stay near the merged edge v-w.
        if (other) {
            double bound = std::numeric_limits<double>::infinity();
            for (std::int32_t t : vtris_[std::size_t(u)]) bound = std::min(bound, rule(t).errorMm);
            bound = std::min(bound, plateBound(gid_[std::size_t(u)]));
            const Vec3& pw = pos_[std::size_t(other->w)];
            const auto within = [&](std::int32_t p) {  // p: input vertex id
                return squaredDistanceToSegment(points_[std::size_t(p)], pv, pw) <= bound * bound;
            };
            if (!within(gid_[std::size_t(u)])) return false;
            for (std::uint64_t key : {gkey(u, v), gkey(u, other->w)}) {
                const auto it = curvePts_.find(key);
                if (it != curvePts_.end())
                    for (std::int32_t p : it->second)
                        if (!within(p)) return false;
            }
        }

        // Surface error: every point of u's triangles (and u itself) finds a triangle of its own
        // interface around v, after the collapse, within the interface's bound.
        if (plan) {
            plan->assign.clear();
            plan->dist.clear();
        }
        // A point is settled by the first triangle within half the bound (the common case, tried
        // from its own triangle on); otherwise the nearest one within the bound takes it.
        const auto place = [&](std::int32_t p, int pairKey, double bound, std::int32_t from) {
            double best = bound * bound;
            const double good = 0.25 * best;
            std::int32_t bestT = -1;
            const Vec3& x = points_[std::size_t(p)];  // p: input vertex id
            const auto consider = [&](std::int32_t t, const Vec3& a, const Vec3& b, const Vec3& c) {
                const double d = squaredDistanceToTriangle(x, a, b, c);
                if (d < best || (d == best && bestT < 0)) {
                    best = d;
                    bestT = t;
                }
                return d <= good;
            };
            bool settled = false;
            const auto own = std::find(moved_.begin(), moved_.end(), from);
            if (own != moved_.end()) {
                const auto& C = newCorners_[std::size_t(own - moved_.begin())];
                settled = consider(from, C[0], C[1], C[2]);
            }
            for (std::size_t m = 0; m < moved_.size() && !settled; ++m) {
                if (pair_[std::size_t(moved_[m])] != pairKey || moved_[m] == from) continue;
                settled = consider(moved_[m], newCorners_[m][0], newCorners_[m][1], newCorners_[m][2]);
            }
            for (std::size_t k = 0; k < vtris_[std::size_t(v)].size() && !settled; ++k) {
                const std::int32_t t = vtris_[std::size_t(v)][k];
                if (pair_[std::size_t(t)] != pairKey || std::find(uv->tris, uv->tris + uv->n, t) != uv->tris + uv->n)
                    continue;
                const Tri& f = tri_[std::size_t(t)];
                settled = consider(t, pos_[f[0]], pos_[f[1]], pos_[f[2]]);
            }
            if (bestT < 0) return false;
            if (plan) {
                plan->assign.emplace_back(p, bestT);
                plan->dist.push_back(float(std::sqrt(best)));
            }
            return true;
        };
        pairsDone_.clear();
        for (std::int32_t t : vtris_[std::size_t(u)]) {
            const int key = pair_[std::size_t(t)];
            if (plan)
                for (std::int32_t p : pts_[std::size_t(t)])
                    if (!place(p, key, boundOf(p, t), t)) return false;
            if (std::find(pairsDone_.begin(), pairsDone_.end(), key) == pairsDone_.end()) {
                pairsDone_.push_back(key);
                if (!place(gid_[std::size_t(u)], key, boundOf(gid_[std::size_t(u)], t), t)) return false;
            }
        }

        if (plan && !newTrianglesNearInput(*plan)) return false;

        // Intersections: every new triangle against everything its box meets (exhaustive), or
        // against the triangles around u's and v's neighbours (local: folds and junctions; the
        // output check catches the rest and triggers an exhaustive rerun).
        if (plan && !opt_.exhaustiveIntersectionChecks) {
            localTris_.clear();
            for (std::int32_t w : nbV_)
                for (std::int32_t t : vtris_[std::size_t(w)]) localTris_.push_back(t);
            for (const Spoke& sp2 : sp)
                for (std::int32_t t : vtris_[std::size_t(sp2.w)]) localTris_.push_back(t);
            std::sort(localTris_.begin(), localTris_.end());
            localTris_.erase(std::unique(localTris_.begin(), localTris_.end()), localTris_.end());
        }
        for (std::size_t m = 0; plan && m < moved_.size(); ++m) {
            const Vec3* P = newCorners_[m].data();
            const Tri newG = global(newTris_[m]);
            const BBox box = boxOf(P[0], P[1], P[2]);
            bool hit = false;
            const auto visit = [&](std::int32_t s) {
                if (hit || s == moved_[m]) return;
                Vec3 Q[3];
                Tri g;
                if (std::size_t(s) >= tri_.size()) {  // another block's triangle
                    g = obstacles_[std::size_t(s) - tri_.size()];
                    for (int i = 0; i < 3; ++i) Q[i] = points_[std::size_t(g[std::size_t(i)])];
                    BBox qb = boxOf(Q[0], Q[1], Q[2]);
                    if ((qb.min.array() > box.max.array()).any() || (box.min.array() > qb.max.array()).any()) return;
                    if (separatedByPlane(P, newG, Q, g) || separatedByPlane(Q, g, P, newG)) return;
                    if (trianglesIntersect(P, newG, Q, g)) hit = true;
                    return;
                }
                if (!alive_[std::size_t(s)]) return;
                if (std::find(uv->tris, uv->tris + uv->n, s) != uv->tris + uv->n) return;
                const auto mi = std::find(moved_.begin(), moved_.end(), s);
                if (mi != moved_.end()) {
                    const std::size_t k = std::size_t(mi - moved_.begin());
                    if (k < m) return;  // pair already tested from the other side
                    g = newTris_[k];
                    for (int i = 0; i < 3; ++i) Q[i] = newCorners_[k][std::size_t(i)];
                } else {
                    g = tri_[std::size_t(s)];
                    for (int i = 0; i < 3; ++i) Q[i] = pos_[std::size_t(g[std::size_t(i)])];
                }
                BBox qb = boxOf(Q[0], Q[1], Q[2]);
                if ((qb.min.array() > box.max.array()).any() || (box.min.array() > qb.max.array()).any()) return;
                g = global(g);
                if (separatedByPlane(P, newG, Q, g) || separatedByPlane(Q, g, P, newG)) return;
                if (trianglesIntersect(P, newG, Q, g)) hit = true;
            };
            if (opt_.exhaustiveIntersectionChecks) grid_.query(box, visit);
            else
                for (std::int32_t t : localTris_) visit(t);
            if (hit) return false;
        }

        if (plan) {
            plan->removed.assign(uv->tris, uv->tris + uv->n);
            plan->moved = moved_;
            plan->curveOther = other ? other->w : -1;
            plan->curvePoints.clear();
            if (other) {
                plan->curvePoints.push_back(gid_[std::size_t(u)]);
                for (std::uint64_t key : {gkey(u, v), gkey(u, other->w), gkey(v, other->w)}) {
                    const auto it = curvePts_.find(key);
                    if (it != curvePts_.end())
                        plan->curvePoints.insert(plan->curvePoints.end(), it->second.begin(), it->second.end());
                }
            }
        }
        return true;
    }

    /// The other direction of the error bound: every new triangle stays within the bound of the
    /// input surface (a triangle can float over a dip whose input points all chose a neighbouring
    /// triangle). Checked at its centroid and edge midpoints (where a flat triangle over a curved
    /// surface is farthest from it), against the input triangles around the nearest input vertex
    /// of the collapse (its removed points and the new triangles' corners), then their
    /// neighbours': a distance to part of the input surface, so never an underestimate.
    bool newTrianglesNearInput(const Plan& plan) {
        near_.clear();
        for (const auto& pt : plan.assign) near_.push_back(pt.first);
        for (const Tri& f : newTris_)
            for (std::int32_t x : f) near_.push_back(gid_[std::size_t(x)]);
        std::sort(near_.begin(), near_.end());
        near_.erase(std::unique(near_.begin(), near_.end()), near_.end());
        const InputSurface& in = *state_.input;
        // positions side by side: every sample scans them all
        nearPos_.clear();
        for (std::int32_t q : near_) nearPos_.push_back(points_[std::size_t(q)]);
        for (std::size_t m = 0; m < moved_.size(); ++m) {
            const auto& C = newCorners_[m];
            const Vec3 samples[4] = {(C[0] + C[1] + C[2]) / 3.0, 0.5 * (C[0] + C[1]), 0.5 * (C[1] + C[2]), 0.5 * (C[2] + C[0])};
            // near the teeth when any corner or the nearest vertex is (NearTeeth.h): the tighter bound
            double cornerBound = std::numeric_limits<double>::infinity();
            for (std::int32_t c : newTris_[m]) cornerBound = std::min(cornerBound, boundOf(gid_[std::size_t(c)], moved_[m]));
            for (const Vec3& x : samples) {
                // p: the nearest input vertex (on the fine interface)
                std::size_t p = 0;
                double d2 = std::numeric_limits<double>::infinity();
                for (std::size_t i = 0; i < nearPos_.size(); ++i) {
                    const double e = (nearPos_[i] - x).squaredNorm();
                    if (e < d2) {
                        d2 = e;
                        p = i;
                    }
                }
                const double bound = std::min(boundOf(near_[p], moved_[m]), cornerBound);
                const double b2 = bound * bound;
                if (d2 <= b2) continue;  // an input vertex (on the input surface) is that close
                // c: the nearest corner, whose input triangles are searched (carried vertices have none)
                std::int32_t c = -1;
                double c2 = std::numeric_limits<double>::infinity();
                for (std::size_t i = 0; i < nearPos_.size(); ++i) {
                    const double e = (nearPos_[i] - x).squaredNorm();
                    if (e < c2 && in.around.count(near_[i]) > 0) {
                        c2 = e;
                        c = near_[i];
                    }
                }
                const auto within = [&](std::int32_t t) {
                    const Tri& f = (*in.tris)[std::size_t(t)];
                    return squaredDistanceToTriangle(x, points_[std::size_t(f[0])], points_[std::size_t(f[1])],
                                                     points_[std::size_t(f[2])]) <= b2;
                };
                if (in.anyAround(c, within)) continue;
                const bool second = in.anyAround(c, [&](std::int32_t t) {
                    for (std::int32_t q : (*in.tris)[std::size_t(t)])
                        if (q != c && in.anyAround(q, within)) return true;
                    return false;
                });
                if (!second) return false;
            }
        }
        return true;
    }

    /// Smallest region wedge over the edges of u's triangles as they are (post = false), or of the
    /// moved triangles after the collapse u -> v that evaluate() is checking (post = true: moved_,
    /// newTris_ filled, u-v's own triangles gone).
    double smallestWedge(std::int32_t u, std::int32_t v, bool post) {
        const auto removedTri = [&](std::int32_t t) {
            return post && std::find(moved_.begin(), moved_.end(), t) == moved_.end() &&
                   std::find(vtris_[std::size_t(u)].begin(), vtris_[std::size_t(u)].end(), t) !=
                       vtris_[std::size_t(u)].end();
        };
        const auto cornersOf = [&](std::int32_t t) -> Tri {
            if (post) {
                const auto it = std::find(moved_.begin(), moved_.end(), t);
                if (it != moved_.end()) return newTris_[std::size_t(it - moved_.begin())];
            }
            return tri_[std::size_t(t)];
        };
        const std::int32_t centre = post ? v : u;
        double smallest = 360;
        const auto& tris = post ? moved_ : vtris_[std::size_t(u)];
        for (std::size_t i = 0; i < tris.size(); ++i) {
            const Tri f = post ? newTris_[i] : tri_[std::size_t(tris[i])];
            for (int k = 0; k < 3; ++k) {
                const std::int32_t a = f[std::size_t(k)], b = f[std::size_t((k + 1) % 3)];
                // Every triangle on a-b holds its endpoint other than the centre, whose list is
                // up to date except for the collapse being checked.
                const std::int32_t hub = a == centre ? b : a;
                wedgeFan_.clear();
                for (std::int32_t t : vtris_[std::size_t(hub)]) {
                    if (removedTri(t)) continue;
                    const Tri g = cornersOf(t);
                    int ia = -1, ib = -1;
                    for (int j = 0; j < 3; ++j) {
                        if (g[std::size_t(j)] == a) ia = j;
                        if (g[std::size_t(j)] == b) ib = j;
                    }
                    if (ia < 0 || ib < 0) continue;
                    const std::int32_t c = g[std::size_t(3 - ia - ib)];
                    wedgeFan_.push_back({pos_[std::size_t(c)], sides_[std::size_t(t)][0], sides_[std::size_t(t)][1],
                                         (ia + 1) % 3 == ib});
                }
                smallest = std::min(smallest, smallestRegionWedgeDeg(pos_[std::size_t(a)], pos_[std::size_t(b)],
                                                                     wedgeFan_.data(), wedgeFan_.size()));
            }
        }
        return smallest;
    }

    /// Makes the collapse u -> v that evaluate(u, v, &plan) accepted just before.
    void apply(std::int32_t u, std::int32_t v, const Plan& plan) {
        for (std::int32_t t : plan.removed) {
            alive_[std::size_t(t)] = 0;
            if (opt_.exhaustiveIntersectionChecks) grid_.remove(t);
            for (std::int32_t x : tri_[std::size_t(t)]) {
                auto& L = vtris_[std::size_t(x)];
                L.erase(std::remove(L.begin(), L.end(), t), L.end());
            }
            pts_[std::size_t(t)].clear();
            pts_[std::size_t(t)].shrink_to_fit();
        }
        for (std::int32_t t : plan.moved) {
            for (auto& x : tri_[std::size_t(t)])
                if (x == u) x = v;
            vtris_[std::size_t(v)].push_back(t);
            pts_[std::size_t(t)].clear();
            const Tri& f = tri_[std::size_t(t)];
            if (opt_.exhaustiveIntersectionChecks) grid_.place(t, boxOf(pos_[f[0]], pos_[f[1]], pos_[f[2]]));
        }
        // Reassign the points of u's old triangles (v's untouched triangles keep theirs).
        for (std::size_t i = 0; i < plan.assign.size(); ++i) {
            const auto [p, t] = plan.assign[i];
            auto& L = pts_[std::size_t(t)];
            if (std::find(L.begin(), L.end(), p) == L.end()) L.push_back(p);
            state_.err[std::size_t(p)] = plan.dist[i];
        }
        // u itself may be placed once per interface; its error is the largest of those.
        float eu = 0;
        for (std::size_t i = 0; i < plan.assign.size(); ++i)
            if (plan.assign[i].first == gid_[std::size_t(u)]) eu = std::max(eu, plan.dist[i]);
        state_.err[std::size_t(gid_[std::size_t(u)])] = eu;
        if (plan.curveOther >= 0) {
            curvePts_.erase(gkey(u, v));
            curvePts_.erase(gkey(u, plan.curveOther));
            auto& L = curvePts_[gkey(v, plan.curveOther)];
            L = plan.curvePoints;
            std::sort(L.begin(), L.end());
            L.erase(std::unique(L.begin(), L.end()), L.end());
        }
        q_[std::size_t(v)].add(q_[std::size_t(u)]);
        vtris_[std::size_t(u)].clear();
        vtris_[std::size_t(u)].shrink_to_fit();
        dead_[std::size_t(u)] = 1;
    }

    /// Pushes u's cheapest collapse toward a neighbour: lazily the cheapest by cost alone, or when
    /// `full` the cheapest that passes every check, none when no neighbour does. `failed`: the
    /// neighbour whose collapse was just refused (nothing changed since: not checked again).
    void schedule(std::int32_t u, bool full = false, std::int32_t failed = -1) {
        ++stamp_[std::size_t(u)];
        if (dead_[std::size_t(u)] || frozen_[std::size_t(u)] || vtris_[std::size_t(u)].empty()) return;
        cand_.clear();
        neighbours(u, cand_);
        costs_.clear();
        const Quadric& qu = q_[std::size_t(u)];
        for (std::int32_t v : cand_) {
            Quadric q = qu;
            q.add(q_[std::size_t(v)]);
            const double cost = std::max(0.0, q.eval(pos_[std::size_t(v)])) +
                                1e-6 * (pos_[std::size_t(u)] - pos_[std::size_t(v)]).squaredNorm();
            costs_.emplace_back(cost, v);
        }
        std::sort(costs_.begin(), costs_.end());
        if (!full) {
            // Lazy: rank by cost only; the pop validates, and only a failure pays for checking
            // every neighbour (most vertices are collapsed toward their cheapest neighbour).
            heap_.push(Candidate{costs_.front().first, u, costs_.front().second, stamp_[std::size_t(u)]});
            return;
        }
        for (const auto& [cost, v] : costs_)
            if (v != failed && evaluate(u, v, &scratchPlan_)) {
                heap_.push(Candidate{cost, u, v, stamp_[std::size_t(u)]});
                return;
            }
    }

    const SimplifyOptions& opt_;
    State& state_;
    const std::vector<Vec3>& points_;   ///< input vertices (ids of pts_ and curve points)
    std::vector<std::int32_t> gid_;     ///< local vertex -> input vertex id
    std::vector<char> frozen_;
    std::vector<Tri> obstacles_;        ///< other blocks' triangles, input ids
    std::vector<std::uint64_t> taken_;
    std::vector<Vec3> pos_;
    std::vector<Tri> tri_;
    std::vector<std::array<Label, 2>> sides_;
    std::vector<int> pair_;
    std::vector<char> alive_;
    std::vector<std::vector<std::int32_t>> vtris_;
    std::vector<std::vector<std::int32_t>> pts_;   ///< removed input vertices placed on each triangle
    std::vector<Quadric> q_;
    std::vector<std::uint32_t> stamp_;
    std::vector<char> dead_;
    std::unordered_map<std::uint64_t, std::vector<std::int32_t>> curvePts_;
    std::vector<std::int32_t> near_;    ///< newTrianglesNearInput's input vertices
    std::vector<Vec3> nearPos_;         ///< and their positions
    std::unordered_map<int, PairRule> rules_;
    TriangleBoxGrid grid_;
    double cosTurn_ = 0.5;
    double cosMinAngle_ = 0.94;
    std::size_t collapses_ = 0;
    std::priority_queue<Candidate> heap_;
    // scratch buffers
    std::vector<Spoke> spokeBuf_;
    std::vector<std::int32_t> nbV_, moved_, ring_, cand_, localTris_;
    std::vector<int> pairsDone_;
    std::vector<std::array<Vec3, 3>> newCorners_;
    std::vector<Tri> newTris_;
    std::vector<EdgeFanTriangle> wedgeFan_;
    std::vector<std::pair<double, std::int32_t>> costs_;
    Plan plan_, scratchPlan_;
};

}  // namespace

nlohmann::json toJson(const SimplifyStats& s) {
    return {{"input_triangles", s.inputTriangles},
            {"output_triangles", s.outputTriangles},
            {"output_vertices", s.outputVertices},
            {"collapses", s.collapses},
            {"triangles_per_kind", s.trianglesPerKind},
            {"max_error_mm", s.maxErrorMm},
            {"max_error_near_teeth_mm", s.maxErrorNearTeethMm},
            {"min_angle_deg", s.minAngleDeg},
            {"min_angle_histogram",
             {{"bins_deg", {0, 5, 10, 15, 20, 30, 40, 60}}, {"triangles", s.minAngleHistogram}}},
            {"seconds", s.seconds},
            {"exhaustive_rerun", s.exhaustiveRerun},
            {"corner_splits", s.cornerSplits},
            {"min_wedge_deg", s.minWedgeDeg},
            {"edges_below_min_wedge", s.edgesBelowMinWedge},
            {"plate_vertices", s.plateVertices}};
}

nlohmann::json toJson(const SimplifyOptions& o) {
    return {{"tooth_error_mm", o.toothErrorMm},       {"pdl_error_mm", o.pdlErrorMm},
            {"bone_error_mm", o.boneErrorMm},         {"bone_far_error_mm", o.boneFarErrorMm},
            {"bone_near_teeth_mm", o.boneNearTeethMm}, {"pdl_max_edge_mm", o.pdlMaxEdgeMm},
            {"cap_max_edge_mm", o.capMaxEdgeMm},      {"tooth_max_edge_mm", o.toothMaxEdgeMm},
            {"bone_max_edge_mm", o.boneMaxEdgeMm},    {"min_angle_deg", o.minAngleDeg},
            {"min_wedge_deg", o.minWedgeDeg},         {"plate_max_mm", o.plateMaxMm},
            {"plate_error_fraction", o.plateErrorFraction}, {"plate_edge_factor", o.plateEdgeFactor}};
}

InterfaceBounds boundsOf(const SimplifyOptions& o) {
    return InterfaceBounds{o.toothErrorMm,  o.pdlErrorMm,   o.boneErrorMm,    o.boneFarErrorMm,
                           o.pdlMaxEdgeMm, o.capMaxEdgeMm, o.toothMaxEdgeMm, o.boneMaxEdgeMm};
}

AdaptiveOptions matchedTo(const SimplifyOptions& options, AdaptiveOptions adaptive) {
    adaptive.bounds = boundsOf(options);
    adaptive.boneNearTeethMm = options.boneNearTeethMm;
    adaptive.minWedgeDeg = options.minWedgeDeg;
    return adaptive;
}

std::string interfaceKind(Label a, Label b) {
    using K = LabelKind;
    const auto kind = [](Label l) { return l == kOutsideLabel ? K::Outside : labelKind(l); };
    K ka = kind(a), kb = kind(b);
    if (ka > kb) std::swap(ka, kb);  // enum order: Outside, Bone, Tooth, Pdl
    if (ka == K::Tooth && kb == K::Pdl) return "tooth/pdl";
    if (ka == K::Bone && kb == K::Pdl) return "pdl/bone";
    if (ka == K::Outside && kb == K::Tooth) return "tooth/outside";
    if (ka == K::Outside && kb == K::Pdl) return "pdl/outside";
    if (ka == K::Outside && kb == K::Bone) return "bone/outside";
    return "other";
}

namespace {

/// Splits the live triangles into cubic blocks (by centroid, grid shifted by offsetMm), marks the
/// vertices shared by two blocks as border, and gives every block the nearby triangles of its
/// neighbours as obstacles. blockMm <= 0: one block with everything, no border.
std::vector<Block> makeBlocks(const State& st, double blockMm, double offsetMm, double marginMm,
                              std::vector<char>& border) {
    const std::size_t nt = st.tris.size();
    border.assign(st.points->size(), 0);
    if (blockMm <= 0) {
        Block all;
        all.tris.resize(nt);
        for (std::size_t t = 0; t < nt; ++t) all.tris[t] = std::int32_t(t);
        return {all};
    }
    const auto& P = *st.points;
    using Cell = std::array<int, 3>;
    std::vector<Cell> cellOf(nt);
    std::map<Cell, std::size_t> index;
    for (std::size_t t = 0; t < nt; ++t) {
        const Tri& f = st.tris[t];
        const Vec3 c = (P[std::size_t(f[0])] + P[std::size_t(f[1])] + P[std::size_t(f[2])]) / 3.0;
        for (int k = 0; k < 3; ++k) cellOf[t][std::size_t(k)] = int(std::floor((c[k] - offsetMm) / blockMm));
        index.emplace(cellOf[t], 0);
    }
    std::size_t n = 0;
    for (auto& [cell, i] : index) i = n++;  // blocks in cell order: deterministic
    std::vector<Block> blocks(n);
    std::vector<std::int32_t> owner(P.size(), -1);
    for (std::size_t t = 0; t < nt; ++t) {
        const std::size_t b = index.at(cellOf[t]);
        blocks[b].tris.push_back(std::int32_t(t));
        for (std::int32_t v : st.tris[t]) {
            if (owner[std::size_t(v)] < 0) owner[std::size_t(v)] = std::int32_t(b);
            else if (owner[std::size_t(v)] != std::int32_t(b)) border[std::size_t(v)] = 1;
        }
    }
    // Obstacles: a neighbour's triangle whose box comes within marginMm of the block's cell.
    for (std::size_t t = 0; t < nt; ++t) {
        const Tri& f = st.tris[t];
        BBox box;
        for (std::int32_t v : f) box.extend(P[std::size_t(v)]);
        const Cell& c = cellOf[t];
        // Per axis, which neighbours (-1, +1) the box comes near; most triangles sit inside their
        // cell and skip the 26 lookups (the test below then decides exactly, as before).
        bool reach[3][2];
        for (int k = 0; k < 3; ++k) {
            reach[k][0] = box.min[k] <= c[std::size_t(k)] * blockMm + offsetMm + marginMm;
            reach[k][1] = box.max[k] >= (c[std::size_t(k)] + 1) * blockMm + offsetMm - marginMm;
        }
        if (!(reach[0][0] || reach[0][1] || reach[1][0] || reach[1][1] || reach[2][0] || reach[2][1])) continue;
        const auto skip = [&](int k, int d) { return d != 0 && !reach[k][d > 0 ? 1 : 0]; };
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    if (!dx && !dy && !dz) continue;
                    if (skip(0, dx) || skip(1, dy) || skip(2, dz)) continue;
                    const Cell nb{c[0] + dx, c[1] + dy, c[2] + dz};
                    const auto it = index.find(nb);
                    if (it == index.end()) continue;
                    bool near = true;
                    for (int k = 0; k < 3 && near; ++k) {
                        const double lo = nb[std::size_t(k)] * blockMm + offsetMm - marginMm;
                        const double hi = (nb[std::size_t(k)] + 1) * blockMm + offsetMm + marginMm;
                        near = box.max[k] >= lo && box.min[k] <= hi;
                    }
                    if (near) blocks[it->second].obstacles.push_back(std::int32_t(t));
                }
    }
    return blocks;
}

/// One pass: every block simplified in parallel (blocks only write their own data), then the
/// results put back in block order.
std::size_t runPass(State& st, double blockMm, double offsetMm, const SimplifyOptions& o, Progress& progress,
                    ProgressStage& stage, double from, double to) {
    std::vector<char> border;
    const double margin = 2.0 * std::max({o.boneMaxEdgeMm, o.toothMaxEdgeMm, o.pdlMaxEdgeMm});
    const std::vector<Block> blocks = makeBlocks(st, blockMm, offsetMm, margin, border);
    std::vector<BlockResult> results(blocks.size());
    std::atomic<std::size_t> done{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 1), [&](const auto& r) {
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
            progress.checkCancelled();
            Simplifier s(st, blocks[b], border, o);
            s.run(progress);
            results[b] = s.result();
            const std::size_t d = ++done;
            if (tbb::this_task_arena::current_thread_index() == 0)
                stage.update(from + (to - from) * double(d) / double(blocks.size()));
        }
    });
    State next;
    std::size_t collapses = 0;
    for (BlockResult& r : results) {
        next.tris.insert(next.tris.end(), r.tris.begin(), r.tris.end());
        next.sides.insert(next.sides.end(), r.sides.begin(), r.sides.end());
        for (auto& p : r.pts) next.pts.push_back(std::move(p));
        for (std::uint64_t key : r.takenCurves) st.curvePts.erase(key);
        for (auto& [key, pts] : r.curves) st.curvePts[key] = std::move(pts);
        collapses += r.collapses;
    }
    st.tris = std::move(next.tris);
    st.sides = std::move(next.sides);
    st.pts = std::move(next.pts);
    return collapses;
}

/// The state's live triangles as a compact complex (seeds not set).
InterfaceComplex complexOf(const State& st, const std::vector<Vec3>& points) {
    InterfaceComplex out;
    std::vector<std::int32_t> remap(points.size(), -1);
    for (std::size_t t = 0; t < st.tris.size(); ++t) {
        Tri f = st.tris[t];
        for (auto& v : f) {
            if (remap[std::size_t(v)] < 0) {
                remap[std::size_t(v)] = std::int32_t(out.surface.vertices.size());
                out.surface.vertices.push_back(points[std::size_t(v)]);
            }
            v = remap[std::size_t(v)];
        }
        out.surface.triangles.push_back(f);
        out.sides.push_back(st.sides[t]);
    }
    return out;
}

}  // namespace

InterfaceComplex simplifyInterfaces(const InterfaceComplex& input, const SimplifyOptions& options,
                                    Progress& progress, SimplifyStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    if (input.sides.size() != input.surface.triangles.size())
        throw Error("simplification: one label pair per triangle is required");
    if (!input.carried.empty() && input.carried.size() != input.surface.triangles.size())
        throw Error("simplification: carried vertices must be given per triangle");
    if (input.sampleErrorMm.size() > input.surface.vertices.size())
        throw Error("simplification: more sample errors than vertices");
    for (double x : {options.toothErrorMm, options.pdlErrorMm, options.boneErrorMm, options.boneFarErrorMm, options.boneNearTeethMm,
                     options.pdlMaxEdgeMm, options.capMaxEdgeMm, options.toothMaxEdgeMm, options.boneMaxEdgeMm,
                     options.plateMaxMm, options.plateErrorFraction, options.plateEdgeFactor})
        if (!(x >= 0) || !std::isfinite(x)) throw Error("simplification: error bounds and edge lengths must be >= 0");
    if (!(options.minAngleDeg >= 0 && options.minAngleDeg < 60))
        throw Error("simplification: minimum angle must be in [0, 60) degrees");
    if (!(options.maxNormalTurnDeg > 0 && options.maxNormalTurnDeg <= 180))
        throw Error("simplification: maximum normal turn must be in (0, 180] degrees");
    if (!(options.minWedgeDeg >= 0 && options.minWedgeDeg < 90))
        throw Error("simplification: minimum region wedge must be in [0, 90) degrees");
    if (!(options.blockMm >= 0)) throw Error("simplification: block size must be >= 0");
    const std::size_t nv = input.surface.vertices.size();
    std::size_t corners = 0;  // vertices past the corners are carried ones (quadrics only for corners)
    for (const Tri& f : input.surface.triangles)
        for (std::int32_t v : f) {
            if (v < 0 || std::size_t(v) >= nv) throw Error("simplification: triangle index out of range");
            corners = std::max(corners, std::size_t(v) + 1);
        }
    for (const auto& carried : input.carried)
        for (std::int32_t v : carried)
            if (v < std::int32_t(corners) || std::size_t(v) >= nv)
                throw Error("simplification: a carried vertex must follow every corner");
    ProgressStage stage(progress, "simplify interfaces");

    // The starting state is rebuilt rather than kept for a possible rerun: a copy would hold
    // ~100 bytes per input vertex for the whole run (about 1.3 GB on a mandible).
    const auto& P = input.surface.vertices;
    std::vector<char> nearTeeth = verticesNearTeeth(input, options.boneNearTeethMm);
    // Thin plates are measured near the teeth only (the crest, pinched PDL): far away the bone is
    // millimetres thick, and the rays would cost seconds for nothing.
    const std::vector<float> plateMm =
        options.plateMaxMm > 0 ? plateThicknessMm(input, nearTeeth, PlateOptions{options.plateMaxMm})
                               : std::vector<float>(nv, std::numeric_limits<float>::infinity());
    const InputSurface inputSurface(input);
    const auto startState = [&] {
        State st;
        st.points = &P;
        st.input = &inputSurface;
        st.tris = input.surface.triangles;
        st.sides = input.sides;
        st.pts.resize(st.tris.size());
        st.quadrics.resize(corners);
        st.err.assign(nv, 0.0f);
        // The adaptive extraction's carried vertices start on their triangles, at their distance.
        for (std::size_t t = 0; t < input.carried.size(); ++t) {
            st.pts[t] = input.carried[t];
            const Tri& f = st.tris[t];
            for (std::int32_t p : st.pts[t])
                st.err[std::size_t(p)] = float(std::sqrt(squaredDistanceToTriangle(P[std::size_t(p)], P[std::size_t(f[0])],
                                                                                   P[std::size_t(f[1])], P[std::size_t(f[2])])));
        }
        st.nearTeeth = nearTeeth;
        st.plateMm = &plateMm;
        st.spentMm = &input.sampleErrorMm;
        for (const Tri& f : st.tris) {
            const Vec3 n2 = (P[std::size_t(f[1])] - P[std::size_t(f[0])]).cross(P[std::size_t(f[2])] - P[std::size_t(f[0])]);
            const double len = n2.norm();
            if (len == 0) continue;
            const Vec3 n = n2 / len;
            for (std::int32_t v : f) st.quadrics[std::size_t(v)].addPlane(n, -n.dot(P[std::size_t(f[0])]), 0.5 * len);
        }
        return st;
    };
    State st = startState();
    // Blocks, blocks shifted by half a block (the first pass's borders inside), then everything.
    std::size_t collapses = 0;
    const auto simplify = [&](const SimplifyOptions& o) {
        if (o.blockMm > 0) {
            collapses += runPass(st, o.blockMm, 0.0, o, progress, stage, 0.0, 0.6);
            collapses += runPass(st, o.blockMm, 0.5 * o.blockMm, o, progress, stage, 0.6, 0.9);
        }
        collapses += runPass(st, 0.0, 0.0, o, progress, stage, 0.9, 0.97);
    };
    simplify(options);
    InterfaceComplex out = complexOf(st, P);
    SelfIntersectionReport check = findSelfIntersections(out.surface);
    bool rerun = false;
    if (!check.pairs.empty() && !options.exhaustiveIntersectionChecks) {
        // The local test missed two sheets meeting away from the collapse: start again with the
        // exhaustive test (slower, but every collapse is then checked against everything).
        st = startState();
        collapses = 0;
        SimplifyOptions exhaustive = options;
        exhaustive.exhaustiveIntersectionChecks = true;
        simplify(exhaustive);
        out = complexOf(st, P);
        check = findSelfIntersections(out.surface);
        rerun = true;
    }
    if (!check.pairs.empty())
        throw Error("simplification: the output has " + std::to_string(check.pairs.size()) +
                    " intersecting triangle pairs (the input surface must be intersection-free)");
    const std::size_t cornerSplits = splitThreeTriangleCorners(out);  // forced slivers (SplitCorners.h)
    out.seeds = seedsInsideShells(out);  // grid seeds may have left a thin region (ShellSeeds.h)
    SimplifyStats local;
    SimplifyStats& s = stats ? *stats : local;
    s = SimplifyStats{};
    s.exhaustiveRerun = rerun;
    s.cornerSplits = cornerSplits;
    s.plateVertices = std::size_t(std::count_if(plateMm.begin(), plateMm.end(), [](float x) { return std::isfinite(x); }));

    s.inputTriangles = input.surface.triangles.size();
    s.outputTriangles = out.surface.triangles.size();
    s.outputVertices = out.surface.vertices.size();
    s.collapses = collapses;
    s.maxErrorMm = st.err.empty() ? 0.0 : double(*std::max_element(st.err.begin(), st.err.end()));
    for (std::size_t v = 0; v < st.err.size(); ++v)
        if (nearTeeth[v]) s.maxErrorNearTeethMm = std::max(s.maxErrorNearTeethMm, double(st.err[v]));
    s.minAngleDeg = 180;
    const double bins[] = {5, 10, 15, 20, 30, 40};
    for (std::size_t t = 0; t < out.surface.triangles.size(); ++t) {
        const Tri& f = out.surface.triangles[t];
        const double a = minAngleDeg(out.surface.vertices[f[0]], out.surface.vertices[f[1]], out.surface.vertices[f[2]]);
        s.minAngleDeg = std::min(s.minAngleDeg, a);
        s.minAngleHistogram[std::size_t(std::upper_bound(std::begin(bins), std::end(bins), a) - std::begin(bins))]++;
        s.trianglesPerKind[interfaceKind(out.sides[t][0], out.sides[t][1])]++;
    }
    const RegionWedgeStats wedges = measureRegionWedges(out, options.minWedgeDeg);
    s.minWedgeDeg = wedges.smallestDeg;
    s.edgesBelowMinWedge = wedges.edgesBelow;
    s.seconds = secondsSince(start);
    return out;
}

}  // namespace jawmesh
