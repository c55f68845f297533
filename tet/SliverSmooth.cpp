// Smoothing and new-node placement for the sliver improver (tet/SliverSmooth.h).
#include "tet/SliverSmooth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace jawmesh {

MovingStar movingStar(const std::vector<Vec3>& nodes, const std::vector<Tet>& tets, std::int32_t v) {
    MovingStar star;
    star.tets.reserve(tets.size());
    for (const Tet& e : tets) {
        MovingStar::Corners c;
        const auto at = std::find(e.begin(), e.end(), v);
        c.moves = at != e.end();
        if (!c.moves) {
            c.fixedScore = sliverScore(nodes[std::size_t(e[0])], nodes[std::size_t(e[1])], nodes[std::size_t(e[2])],
                                       nodes[std::size_t(e[3])]);
            star.tets.push_back(c);
            continue;
        }
        // moving the node to the front takes k swaps of neighbours, each flipping the orientation
        const std::ptrdiff_t k = at - e.begin();
        std::array<std::int32_t, 3> rest{};
        for (std::ptrdiff_t i = 0, j = 0; i < 4; ++i)
            if (i != k) rest[std::size_t(j++)] = e[std::size_t(i)];
        c.a = nodes[std::size_t(rest[0])];
        c.b = nodes[std::size_t(rest[1])];
        c.c = nodes[std::size_t(rest[2])];
        c.opposite = (c.b - c.a).cross(c.c - c.a);
        c.oppositeLength = c.opposite.norm();
        c.sign = k % 2 == 0 ? 1.0 : -1.0;
        star.tets.push_back(c);
    }
    return star;
}

namespace {

/// sliverScore of the tet (p, a, b, c) of a moving star (p the node), the orientation taken
/// from c.sign: the face normals all point out, or all in, so their angles are the same.
double movingScore(const MovingStar::Corners& c, const Vec3& p) {
    if (!c.moves) return c.fixedScore;
    const Vec3 pa = c.a - p, pb = c.b - p, pc = c.c - p;
    if (!(c.sign * pa.dot(c.opposite) > 0) || !(c.oppositeLength > 0)) return kInvalidScore;
    const Vec3 n[4] = {c.opposite, pc.cross(pb), pa.cross(pc), pb.cross(pa)};
    double len[4] = {c.oppositeLength, 0, 0, 0};
    for (int k = 1; k < 4; ++k) {
        len[k] = n[k].norm();
        if (!(len[k] > 0)) return kInvalidScore;
    }
    return scoreOfFaceNormals(n, len);
}

/// Ranks the star's tets by their score with the node at p, worst first (star.worstFirst).
void rankWorstFirst(MovingStar& star, const Vec3& p) {
    std::vector<double> score(star.tets.size());
    for (std::size_t i = 0; i < score.size(); ++i) score[i] = movingScore(star.tets[i], p);
    star.worstFirst.resize(score.size());
    for (std::size_t i = 0; i < score.size(); ++i) star.worstFirst[i] = std::uint32_t(i);
    std::stable_sort(star.worstFirst.begin(), star.worstFirst.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return score[a] < score[b]; });
}

/// Whether the tets cannot beat `cannotBeat` (in worst-first order, stopping when that shows).
bool cannotWin(const MovingStar& star, const Vec3& p, double target, const Objective& cannotBeat) {
    Objective o;
    for (std::uint32_t i : star.worstFirst) {
        o.add(movingScore(star.tets[i], p), target);
        if (o.worst < cannotBeat.worst || o.deficit > cannotBeat.deficit) return true;
    }
    return false;
}

}  // namespace

Objective objectiveWith(const MovingStar& star, const Vec3& p, double target, const Objective& cannotBeat) {
    // Screened first: a sum in another order may differ in its last bit, so only "cannot win" is
    // taken from the screen (its bound has slack far above rounding, Objective::hopelessBelow).
    // Only against a valid bound: an invalid tet (worst kInvalidScore) then cannot win either way.
    if (!star.worstFirst.empty() && cannotBeat.worst > kInvalidScore && cannotWin(star, p, target, cannotBeat))
        return Objective::hopeless();
    Objective o;
    for (const MovingStar::Corners& c : star.tets) {
        o.add(movingScore(c, p), target);
        if (o.worst <= kInvalidScore) break;
        // The worst score only falls and the shortfall only grows as tets are added.
        if (o.worst < cannotBeat.worst || o.deficit > cannotBeat.deficit) return Objective::hopeless();
    }
    return o;
}

Objective objectiveWith(const std::vector<Vec3>& nodes, const std::vector<Tet>& tets, std::int32_t v, const Vec3& p, double target,
                        const Objective& cannotBeat) {
    return objectiveWith(movingStar(nodes, tets, v), p, target, cannotBeat);
}

Objective objectiveOf(const TetMeshEditor& mesh, const std::vector<std::int32_t>& tets, double target) {
    Objective o;
    for (auto t : tets) o.add(mesh.score(t), target);
    return o;
}

std::pair<Vec3, Objective> bestPosition(const TetMeshEditor& mesh, const std::vector<Tet>& tets, std::int32_t v, Vec3 start,
                                        double target) {
    MovingStar star = movingStar(mesh.nodes(), tets, v);
    Objective best = objectiveWith(star, start, target);
    rankWorstFirst(star, start);
    double shortest = std::numeric_limits<double>::infinity();
    for (const Tet& e : tets)
        for (auto w : e)
            if (w != v) shortest = std::min(shortest, (mesh.node(w) - start).norm());
    if (!std::isfinite(shortest) || shortest <= 0) return {start, best};
    // the 6 axes and 8 diagonals, as unit vectors
    static const std::array<Vec3, 14> dirs = [] {
        const double d[14][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},   {0, -1, 0},  {0, 0, 1},   {0, 0, -1},  {1, 1, 1},
                                 {1, 1, -1}, {1, -1, 1}, {1, -1, -1}, {-1, 1, 1}, {-1, 1, -1}, {-1, -1, 1}, {-1, -1, -1}};
        std::array<Vec3, 14> unit;
        for (std::size_t k = 0; k < unit.size(); ++k) unit[k] = Vec3(d[k][0], d[k][1], d[k][2]).normalized();
        return unit;
    }();
    double h = 0.25 * shortest;
    Vec3 p = start;
    for (int iter = 0; iter < 60 && h > 1e-4 * shortest; ++iter) {
        // the 14 trial positions in order, each scored only as far as it can still beat the best so far
        Objective stepBest = best;
        Vec3 stepP = p;
        for (const Vec3& dir : dirs) {
            const Vec3 trial = p + h * dir;
            const Objective o = objectiveWith(star, trial, target, stepBest.hopelessBelow(dirs.size()));
            if (o.betterThan(stepBest)) {
                stepBest = o;
                stepP = trial;
            }
        }
        if (stepBest.betterThan(best)) {
            best = stepBest;
            p = stepP;
            rankWorstFirst(star, p);
        } else {
            h *= 0.5;
        }
    }
    return {p, best};
}

std::pair<Vec3, Objective> bestOfStarts(const TetMeshEditor& mesh, const std::vector<Tet>& fresh, std::int32_t m,
                                        const std::vector<std::int32_t>& old, double target) {
    Vec3 centroid = Vec3::Zero();
    for (auto t : old)
        for (auto v : mesh.tet(t)) centroid += mesh.node(v);
    centroid /= double(4 * old.size());
    auto first = bestPosition(mesh, fresh, m, mesh.node(m), target);
    auto second = bestPosition(mesh, fresh, m, centroid, target);
    return second.second.betterThan(first.second) ? second : first;
}

namespace {

/// Moves v to its best position when the rule accepts it over where v is.
bool smoothNode(TetMeshEditor& mesh, std::int32_t v, Acceptance& accept) {
    std::vector<Tet> tets;
    for (auto t : mesh.star(v)) tets.push_back(mesh.tet(t));
    const Objective before = objectiveWith(mesh.nodes(), tets, v, mesh.node(v), accept.target());
    const auto [p, after] = bestPosition(mesh, tets, v, mesh.node(v), accept.target());
    if (!accept(after, before)) return false;
    mesh.move(v, p);
    return true;
}

}  // namespace

bool smoothAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats) {
    const Tet e = mesh.tet(t);
    for (auto v : e)
        if (!mesh.fixed(v) && smoothNode(mesh, v, accept)) {
            ++stats.smoothed;
            return true;
        }
    return false;
}

}  // namespace jawmesh
