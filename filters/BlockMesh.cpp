// One block's mesh for the simplification (BlockMesh.h): setup from the state, topology queries,
// bounds, and the collapse itself.
#include "filters/BlockMesh.h"

#include "io/Angles.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace jawmesh::simplify {
namespace {

/// Cell of the intersection grid: a few of the block's shortest edges.
double cellSize(const State& st, const Block& b) {
    double e = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < std::min<std::size_t>(b.tris.size(), 512); ++i) {
        const Tri& f = st.tris[std::size_t(b.tris[i])];
        e = std::min(e, ((*st.points)[std::size_t(f[0])] - (*st.points)[std::size_t(f[1])]).norm());
    }
    return std::isfinite(e) && e > 0 ? 6.0 * std::max(e, 1e-3) : 0.3;
}

}  // namespace

BlockMesh::BlockMesh(State& st, const Block& block, const std::vector<char>& border, const SimplifyOptions& o)
    : opt(o), state(st), points(*st.points), grid(cellSize(st, block)) {
    copyTriangles(block);
    copyVertices(border);
    cosTurn = std::cos(o.maxNormalTurnDeg * kPi / 180.0);
    cosMinAngle = std::cos(o.minAngleDeg * kPi / 180.0);
    indexTriangles();
    placeObstacles(block);
}

/// The block's triangles in local ids (gid: the input id of each).
void BlockMesh::copyTriangles(const Block& block) {
    std::unordered_map<std::int32_t, std::int32_t> local;
    local.reserve(block.tris.size());
    const auto localOf = [&](std::int32_t g) {
        const auto [it, fresh] = local.emplace(g, std::int32_t(gid.size()));
        if (fresh) gid.push_back(g);
        return it->second;
    };
    const std::size_t nt = block.tris.size();
    tri.resize(nt);
    sides.resize(nt);
    pts.resize(nt);
    for (std::size_t t = 0; t < nt; ++t) {
        const std::size_t g = std::size_t(block.tris[t]);
        for (int k = 0; k < 3; ++k) tri[t][k] = localOf(state.tris[g][k]);
        sides[t] = state.sides[g];
        pts[t] = state.pts[g];
    }
}

void BlockMesh::copyVertices(const std::vector<char>& border) {
    const std::size_t nv = gid.size(), nt = tri.size();
    pos.resize(nv);
    q.resize(nv);
    frozen.resize(nv);
    for (std::size_t l = 0; l < nv; ++l) {
        pos[l] = points[std::size_t(gid[l])];
        q[l] = state.quadrics[std::size_t(gid[l])];
        frozen[l] = border[std::size_t(gid[l])];
    }
    pair.resize(nt);
    alive.assign(nt, 1);
    vtris.resize(nv);
    dead.assign(nv, 0);
}

/// Triangles around each vertex, label pairs and their rules, the grid, and the curve edges this
/// block owns: those with an endpoint that may move.
void BlockMesh::indexTriangles() {
    for (std::size_t t = 0; t < tri.size(); ++t) {
        const Tri& f = tri[t];
        for (int k = 0; k < 3; ++k) vtris[std::size_t(f[k])].push_back(std::int32_t(t));
        pair[t] = interfaceMarker(sides[t][0], sides[t][1]);
        rules.try_emplace(pair[t], ruleFor(sides[t][0], sides[t][1]));
        if (opt.exhaustiveIntersectionChecks) grid.place(std::int32_t(t), boxOf(pos[f[0]], pos[f[1]], pos[f[2]]));
        for (int k = 0; k < 3; ++k) {
            const std::int32_t a = f[k], b = f[(k + 1) % 3];
            if (frozen[std::size_t(a)] && frozen[std::size_t(b)]) continue;
            const std::uint64_t key = edgeKey(gid[std::size_t(a)], gid[std::size_t(b)]);
            const auto it = state.curvePts.find(key);
            if (it != state.curvePts.end() && !curvePts.count(key)) {
                curvePts.emplace(key, it->second);
                taken.push_back(key);
            }
        }
    }
}

/// Other blocks' triangles near this one, into the grid after the block's own.
void BlockMesh::placeObstacles(const Block& block) {
    const std::size_t nt = tri.size();
    obstacles.reserve(block.obstacles.size());
    for (std::int32_t g : opt.exhaustiveIntersectionChecks ? block.obstacles : std::vector<std::int32_t>{}) {
        const Tri& f = state.tris[std::size_t(g)];
        obstacles.push_back(f);
        grid.place(std::int32_t(nt + obstacles.size() - 1),
                   boxOf(points[std::size_t(f[0])], points[std::size_t(f[1])], points[std::size_t(f[2])]));
    }
}

PairRule BlockMesh::ruleFor(Label a, Label b) const {
    const InterfaceBounds bounds = boundsOf(opt);
    return {bounds.boundMm(a, b, true), bounds.maxEdgeMm(a, b), bounds.boundMm(a, b, false)};
}

double BlockMesh::fineBoundOf(std::int32_t p, std::int32_t t) const {
    const PairRule& r = rule(t);
    return std::min(state.nearTeeth[std::size_t(p)] ? r.errorMm : r.farErrorMm, plateBound(p));
}

double BlockMesh::boundOf(std::int32_t p, std::int32_t t) const {
    const auto& S = *state.spentMm;
    const double spent = std::size_t(p) < S.size() ? double(S[std::size_t(p)]) : 0.0;
    return std::max(0.0, fineBoundOf(p, t) - spent);
}

double BlockMesh::plateBound(std::int32_t p) const {
    return opt.plateErrorFraction * double((*state.plateMm)[std::size_t(p)]);
}

double BlockMesh::plateEdge(std::int32_t a, std::int32_t b, std::int32_t c) const {
    const auto& T = *state.plateMm;
    return opt.plateEdgeFactor * double(std::min({T[std::size_t(gid[std::size_t(a)])], T[std::size_t(gid[std::size_t(b)])],
                                                  T[std::size_t(gid[std::size_t(c)])]}));
}

void BlockMesh::neighbours(std::int32_t u, std::vector<std::int32_t>& out) const {
    for (std::int32_t t : vtris[std::size_t(u)])
        for (std::int32_t x : tri[std::size_t(t)])
            if (x != u) out.push_back(x);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

bool BlockMesh::spokes(std::int32_t u, std::vector<Spoke>& out) const {
    out.clear();
    for (std::int32_t t : vtris[std::size_t(u)])
        for (std::int32_t x : tri[std::size_t(t)]) {
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
            if (pair[std::size_t(s.tris[k])] != pair[std::size_t(s.tris[0])]) s.feature = true;
    }
    std::sort(out.begin(), out.end(), [](const Spoke& a, const Spoke& b) { return a.w < b.w; });
    return true;
}

bool BlockMesh::singleFan(std::int32_t u, const std::vector<Spoke>& sp) const {
    const auto& T = vtris[std::size_t(u)];
    if (T.size() != sp.size() || T.size() < 3) return false;
    std::int32_t t = T[0];
    std::int32_t w = third(t, u, tri[std::size_t(t)][0] == u ? tri[std::size_t(t)][1] : tri[std::size_t(t)][0]);
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

void BlockMesh::apply(std::int32_t u, std::int32_t v, const CollapsePlan& plan) {
    for (std::int32_t t : plan.removed) {
        alive[std::size_t(t)] = 0;
        if (opt.exhaustiveIntersectionChecks) grid.remove(t);
        for (std::int32_t x : tri[std::size_t(t)]) {
            auto& L = vtris[std::size_t(x)];
            L.erase(std::remove(L.begin(), L.end(), t), L.end());
        }
        pts[std::size_t(t)].clear();
        pts[std::size_t(t)].shrink_to_fit();
    }
    for (std::int32_t t : plan.moved) {
        for (auto& x : tri[std::size_t(t)])
            if (x == u) x = v;
        vtris[std::size_t(v)].push_back(t);
        pts[std::size_t(t)].clear();
        const Tri& f = tri[std::size_t(t)];
        if (opt.exhaustiveIntersectionChecks) grid.place(t, boxOf(pos[f[0]], pos[f[1]], pos[f[2]]));
    }
    // Reassign the points of u's old triangles (v's untouched triangles keep theirs). A point is
    // in one list per interface and placed once per interface, so it is never there already (a
    // search of the list for it was quadratic in the lists, which grow to hundreds of points).
    for (std::size_t i = 0; i < plan.assign.size(); ++i) {
        const auto [p, t] = plan.assign[i];
        pts[std::size_t(t)].push_back(p);
        state.err[std::size_t(p)] = plan.dist[i];
    }
    // u itself may be placed once per interface; its error is the largest of those.
    float eu = 0;
    for (std::size_t i = 0; i < plan.assign.size(); ++i)
        if (plan.assign[i].first == gid[std::size_t(u)]) eu = std::max(eu, plan.dist[i]);
    state.err[std::size_t(gid[std::size_t(u)])] = eu;
    if (plan.curveOther >= 0) {
        curvePts.erase(gkey(u, v));
        curvePts.erase(gkey(u, plan.curveOther));
        auto& L = curvePts[gkey(v, plan.curveOther)];
        L = plan.curvePoints;
        std::sort(L.begin(), L.end());
        L.erase(std::unique(L.begin(), L.end()), L.end());
    }
    q[std::size_t(v)].add(q[std::size_t(u)]);
    vtris[std::size_t(u)].clear();
    vtris[std::size_t(u)].shrink_to_fit();
    dead[std::size_t(u)] = 1;
}

BlockResult BlockMesh::result() {
    BlockResult r;
    for (std::size_t t = 0; t < tri.size(); ++t) {
        if (!alive[t]) continue;
        r.tris.push_back(global(tri[t]));
        r.sides.push_back(sides[t]);
        r.pts.push_back(std::move(pts[t]));
    }
    for (std::size_t l = 0; l < gid.size(); ++l)
        if (!frozen[l]) state.quadrics[std::size_t(gid[l])] = q[l];
    r.takenCurves = std::move(taken);
    r.curves = std::move(curvePts);
    return r;
}

}  // namespace jawmesh::simplify
