// The collapse queue of one block (BlockSimplifier.h).
#include "filters/BlockSimplifier.h"

#include <algorithm>

namespace jawmesh::simplify {

BlockSimplifier::BlockSimplifier(State& state, const Block& block, const std::vector<char>& border,
                                 const SimplifyOptions& options)
    : mesh_(state, block, border, options), check_(mesh_) {
    stamp_.assign(mesh_.pos.size(), 0);
    refused_.resize(mesh_.pos.size());
}

void BlockSimplifier::run(Progress& progress) {
    const std::size_t nv = mesh_.pos.size();
    for (std::size_t u = 0; u < nv; ++u)
        if (!mesh_.state.settled[std::size_t(mesh_.gid[u])]) schedule(std::int32_t(u));
    std::size_t popped = 0;
    while (!heap_.empty()) {
        const Candidate c = heap_.top();
        heap_.pop();
        if (++popped % 65536 == 0) progress.checkCancelled();
        if (mesh_.dead[std::size_t(c.u)] || stamp_[std::size_t(c.u)] != c.stamp) continue;
        if (!check_.plan(c.u, c.v, plan_)) {
            refused_[std::size_t(c.u)].push_back(c.v);
            schedule(c.u, true);  // terminates: each refusal leaves one neighbour fewer to try
            continue;
        }
        mesh_.apply(c.u, c.v, plan_);
        ++collapses_;
        // Everything whose neighbourhood changed gets a fresh candidate.
        ring_.clear();
        mesh_.neighbours(c.v, ring_);
        const std::vector<std::int32_t> ring = ring_;
        schedule(c.v);
        for (std::int32_t w : ring) schedule(w);
        for (std::int32_t w : ring)
            if (mesh_.frozen[std::size_t(w)]) touchedFrozen_.push_back(mesh_.gid[std::size_t(w)]);
    }
}

BlockResult BlockSimplifier::result() {
    BlockResult r = mesh_.result();
    r.collapses = collapses_;
    // the queue is empty: every free vertex left has had each of its collapses refused
    for (std::size_t l = 0; l < mesh_.gid.size(); ++l)
        if (!mesh_.frozen[l] && !mesh_.dead[l]) mesh_.state.settled[std::size_t(mesh_.gid[l])] = 1;
    std::sort(touchedFrozen_.begin(), touchedFrozen_.end());
    touchedFrozen_.erase(std::unique(touchedFrozen_.begin(), touchedFrozen_.end()), touchedFrozen_.end());
    r.touchedFrozen = std::move(touchedFrozen_);
    return r;
}

/// The ranking: the quadric error of u's and v's planes at v, plus a little of the edge's length
/// (ties). No check: a candidate is checked when it is popped.
double BlockSimplifier::collapseCost(std::int32_t u, std::int32_t v) const {
    Quadric q = mesh_.q[std::size_t(u)];
    q.add(mesh_.q[std::size_t(v)]);
    return std::max(0.0, q.eval(mesh_.pos[std::size_t(v)])) +
           1e-6 * (mesh_.pos[std::size_t(u)] - mesh_.pos[std::size_t(v)]).squaredNorm();
}

/// Pushes u's cheapest collapse toward a neighbour, ranked by cost alone; the pop runs the whole
/// check. After a refusal, the cheapest neighbour not refused since u's neighbourhood last changed
/// that passes the cheap tests (the dear ones run once, at the pop: checking them here too had
/// every collapse that follows a refusal checked twice); none when no neighbour is left.
void BlockSimplifier::schedule(std::int32_t u, bool afterRefusal) {
    ++stamp_[std::size_t(u)];
    std::vector<std::int32_t>& refused = refused_[std::size_t(u)];
    if (!afterRefusal) refused.clear();
    if (mesh_.dead[std::size_t(u)] || mesh_.frozen[std::size_t(u)] || mesh_.vtris[std::size_t(u)].empty()) return;
    cand_.clear();
    mesh_.neighbours(u, cand_);
    costs_.clear();
    for (std::int32_t v : cand_) costs_.emplace_back(collapseCost(u, v), v);
    std::sort(costs_.begin(), costs_.end());
    for (const auto& [cost, v] : costs_) {
        if (std::find(refused.begin(), refused.end(), v) != refused.end()) continue;
        if (afterRefusal && !check_.cheapTestsPass(u, v)) continue;
        heap_.push(Candidate{cost, u, v, stamp_[std::size_t(u)]});
        return;
    }
}

}  // namespace jawmesh::simplify
