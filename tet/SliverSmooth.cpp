// Smoothing and new-node placement for the sliver improver (tet/SliverSmooth.h).
#include "tet/SliverSmooth.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <limits>

namespace jawmesh {

Objective objectiveWith(const std::vector<Vec3>& nodes, const std::vector<Tet>& tets, std::int32_t v, const Vec3& p, double target,
                        const Objective& cannotBeat) {
    Objective o;
    for (const Tet& e : tets) {
        const Vec3* q[4];
        for (int k = 0; k < 4; ++k) q[k] = e[std::size_t(k)] == v ? &p : &nodes[std::size_t(e[std::size_t(k)])];
        o.add(sliverScore(*q[0], *q[1], *q[2], *q[3]), target);
        if (o.worst <= kInvalidScore) break;
        // The worst score only falls and the shortfall only grows as tets are added.
        if (o.worst < cannotBeat.worst || o.deficit > cannotBeat.deficit) return Objective::hopeless();
    }
    return o;
}

Objective objectiveOf(const TetMeshEditor& mesh, const std::vector<std::int32_t>& tets, double target) {
    Objective o;
    for (auto t : tets) o.add(mesh.score(t), target);
    return o;
}

std::pair<Vec3, Objective> bestPosition(const TetMeshEditor& mesh, const std::vector<Tet>& tets, std::int32_t v, Vec3 start,
                                        double target) {
    Objective best = objectiveWith(mesh.nodes(), tets, v, start, target);
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
        // the 14 trial positions are scored in parallel, then compared in order (as one thread would)
        std::array<Vec3, 14> trial;
        std::array<Objective, 14> trialScore;
        for (std::size_t k = 0; k < trial.size(); ++k) trial[k] = p + h * dirs[k];
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, trial.size(), 7), [&](const auto& r) {
            for (std::size_t k = r.begin(); k != r.end(); ++k)
                trialScore[k] = objectiveWith(mesh.nodes(), tets, v, trial[k], target, best.hopelessBelow(trial.size()));
        });
        Objective stepBest = best;
        Vec3 stepP = p;
        for (std::size_t k = 0; k < trial.size(); ++k)
            if (trialScore[k].betterThan(stepBest)) {
                stepBest = trialScore[k];
                stepP = trial[k];
            }
        if (stepBest.betterThan(best)) {
            best = stepBest;
            p = stepP;
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
