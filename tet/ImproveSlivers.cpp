#include "tet/ImproveSlivers.h"

#include "io/Error.h"
#include "tet/ElementQuality.h"
#include "tet/TetFaceAdjacency.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace jawmesh {

namespace {

constexpr double kInvalid = -3.0;  // below every cosine-based score: an inverted or flat tet

/// Score of a tet: minus the cosine of its smallest interior dihedral angle (monotone in that
/// angle, cheaper than the angle itself); kInvalid when not positively oriented.
double score(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const Vec3 u = b - a, v = c - a, w = d - a;
    if (!(u.dot(v.cross(w)) > 0)) return kInvalid;
    const Vec3 n[4] = {(c - b).cross(d - b), (d - a).cross(c - a), (b - a).cross(d - a), (c - a).cross(b - a)};
    double len[4];
    for (int k = 0; k < 4; ++k) {
        len[k] = n[k].norm();
        if (!(len[k] > 0)) return kInvalid;
    }
    double worstCos = -1.0;  // cosine of the interior dihedral angle = -cos(angle of outward normals)
    for (int k = 0; k < 4; ++k)
        for (int l = k + 1; l < 4; ++l) worstCos = std::max(worstCos, -n[k].dot(n[l]) / (len[k] * len[l]));
    return -worstCos;
}

double scoreToDeg(double s) { return s <= kInvalid ? 0.0 : std::acos(std::clamp(-s, -1.0, 1.0)) * 180.0 / M_PI; }

/// What a local operation optimises over the tets it changes: the worst score and the total
/// shortfall below the target (so a bad tet next to a worse one that no operation can fix is
/// still improved).
struct Objective {
    double worst = std::numeric_limits<double>::infinity();
    double deficit = 0;
    void add(double s, double target) {
        worst = std::min(worst, s);
        deficit += std::max(0.0, target - s);
    }
    /// Better when neither the worst score nor the shortfall gets worse and one of them improves
    /// (Pareto). Trading one for the other lets the improver churn: raising the worst tet of a
    /// star while pushing several good ones under the target (the shared mandible: 260 tets left
    /// under 10 degrees that way, 62 with this rule, from TetGen's 27,619).
    bool betterThan(const Objective& o) const {
        if (worst < o.worst - 1e-12 || deficit > o.deficit + 1e-12) return false;
        return worst > o.worst + 1e-9 || deficit < o.deficit - 1e-9;
    }
};

double signedVolume6(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return (b - a).dot((c - a).cross(d - a)); }

/// q strictly inside the circumsphere of the tet a, b, c, d (false for a degenerate tet).
bool insideCircumsphere(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& q) {
    const Vec3 u = b - a, v = c - a, w = d - a;
    const double det = 2 * u.dot(v.cross(w));
    if (det == 0) return false;
    const Vec3 centre = (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / det;
    return (q - a - centre).squaredNorm() < centre.squaredNorm();
}

/// Which outer faces of a cavity to leave out of its star (sorted node triples).
using FaceFilter = std::function<bool(const std::array<std::int32_t, 3>&)>;

class SliverImprover {
public:
    SliverImprover(TetMesh& m, const SliverOptions& o)
        : m_(m), target_(-std::cos(o.targetMinDihedralDeg * M_PI / 180.0)), interfaceInsertions_(o.interfaceInsertions) {
        alive_.assign(m.tets.size(), 1);
        star_.resize(m.nodes.size());
        for (std::size_t t = 0; t < m.tets.size(); ++t)
            for (auto v : m.tets[t]) star_[std::size_t(v)].push_back(std::int32_t(t));
        // Vertices on an interface or the mesh boundary are fixed.
        fixed_.assign(m.nodes.size(), 0);
        const TetFaceAdjacency adj = tetFaceAdjacency(m);
        for (std::size_t g = 0; g < adj.groupCount(); ++g) {
            const auto& f0 = adj.faces[std::size_t(adj.groupStart[g])];
            if (!insideOneRegion(adj, m, g))
                for (auto v : f0.key) fixed_[std::size_t(v)] = 1;
        }
    }

    double tetScore(std::int32_t t) const {
        const Tet& e = m_.tets[std::size_t(t)];
        return score(P(e[0]), P(e[1]), P(e[2]), P(e[3]));
    }

    /// The bad tets, worst first (ties by index).
    std::vector<std::int32_t> badTets() const {
        // scored in parallel (every pass scores all tets), collected in index order
        std::vector<double> scores(m_.tets.size(), kInvalid);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m_.tets.size(), 8192), [&](const auto& r) {
            for (std::size_t t = r.begin(); t != r.end(); ++t)
                if (alive_[t]) scores[t] = tetScore(std::int32_t(t));
        });
        std::vector<std::pair<double, std::int32_t>> bad;
        for (std::size_t t = 0; t < m_.tets.size(); ++t)
            if (alive_[t] && scores[t] < target_) bad.emplace_back(scores[t], std::int32_t(t));
        std::sort(bad.begin(), bad.end());
        std::vector<std::int32_t> out;
        for (auto& b : bad) out.push_back(b.second);
        return out;
    }

    /// One attempt to improve tet t; true when something was changed.
    bool improve(std::int32_t t, SliverStats& st) {
        if (!alive_[std::size_t(t)] || tetScore(t) >= target_) return false;
        const Tet e = m_.tets[std::size_t(t)];
        for (auto v : e)
            if (!fixed_[std::size_t(v)] && smooth(v)) {
                ++st.smoothed;
                return true;
            }
        if (flip23Around(t, st) || removeEdgeAround(t, st)) return true;
        return splitAround(t, st) || splitFaceAround(t, st) || starCavityAround(t, st) ||
               (interfaceInsertions_ && insertOnInterfaceAround(t, st));
    }

    /// Lookahead, for a tet at a local optimum of the hill climbing (no single operation raises
    /// the tets it changes): each candidate of each operation is made whether it helps or not, the
    /// bad tets around what it made are then improved as usual (with a lookahead of depth - 1
    /// where that alone fails), and the whole is kept only when fewer tets are left under the
    /// target among those it changed (trialHelped); otherwise it is undone. A flip or a split
    /// that first makes things worse can open the way to a smoothing or another flip: the
    /// slivers a single step cannot mend.
    /// Lets the lookahead make `more` trials from now on, then no more.
    void limitTrials(std::size_t more) { trialLimit_ = trialsMade_ + more; }

    bool improveWithLookahead(std::int32_t t, int depth, SliverStats& st) {
        if (!alive_[std::size_t(t)] || tetScore(t) >= target_) return false;
        using Operation = bool (SliverImprover::*)(std::int32_t, SliverStats&);
        static constexpr Operation operations[] = {&SliverImprover::flip23Around,    &SliverImprover::removeEdgeAround,
                                                   &SliverImprover::splitAround,     &SliverImprover::splitFaceAround,
                                                   &SliverImprover::starCavityAround, &SliverImprover::insertOnInterfaceAround};
        for (Operation op : operations) {
            if (op == &SliverImprover::insertOnInterfaceAround && !interfaceInsertions_) continue;
            for (int k = 0;; ++k) {
                if (trialsMade_ >= trialLimit_) return false;
                ++trialsMade_;
                SliverStats trial = st;
                beginTrial();
                forcedCandidate_ = k;
                candidatesSeen_ = 0;
                const bool made = (this->*op)(t, trial);
                const int seen = candidatesSeen_;
                forcedCandidate_ = -1;
                if (made) {
                    improveAround(depth - 1, trial);
                    if (trialHelped()) {
                        keepTrial();
                        st = trial;
                        ++st.lookaheads;
                        return true;
                    }
                }
                undoTrial();
                if (seen <= k) break;  // the operation has no k-th candidate
            }
        }
        return false;
    }

    /// The last resort (SliverOptions::interfacePushMm): for tet t, its interface nodes inside the
    /// mesh, lowest over their opposite face first, are tried pushed straight away from that face
    /// by up to maxMm; the first push that raises the tets around the node is made. Records the
    /// volume each label gains or loses, for the final volume check.
    bool pushInterfaceNode(std::int32_t t, double maxMm, std::map<Label, double>& volumeChange, SliverStats& st) {
        if (!alive_[std::size_t(t)] || tetScore(t) >= target_) return false;
        const Tet e = m_.tets[std::size_t(t)];
        std::array<std::pair<double, int>, 4> order;
        std::array<Vec3, 4> away;
        for (int k = 0; k < 4; ++k) {
            const Vec3 &a = P(e[std::size_t((k + 1) % 4)]), &b = P(e[std::size_t((k + 2) % 4)]), &c = P(e[std::size_t((k + 3) % 4)]);
            Vec3 n = (b - a).cross(c - a).normalized();
            if (n.dot(P(e[std::size_t(k)]) - a) < 0) n = -n;
            away[std::size_t(k)] = n;
            order[std::size_t(k)] = {n.dot(P(e[std::size_t(k)]) - a), k};
        }
        std::sort(order.begin(), order.end());
        for (const auto& [height, k] : order) {
            const std::int32_t v = e[std::size_t(k)];
            if (!fixed_[std::size_t(v)] || pushed_.count(v) || onMeshBoundary(v)) continue;
            std::vector<Tet> tets;
            for (auto s : star_[std::size_t(v)]) tets.push_back(m_.tets[std::size_t(s)]);
            const Objective before = scoreWith(tets, v, P(v));
            Objective best = before;
            double bestStep = 0;
            for (int i = 1; i <= 8; ++i) {
                const double step = maxMm * i / 8.0;
                const Objective o = scoreWith(tets, v, P(v) + step * away[std::size_t(k)]);
                if (o.betterThan(best)) {
                    best = o;
                    bestStep = step;
                }
            }
            if (bestStep == 0) continue;
            for (auto s : star_[std::size_t(v)]) volumeChange[m_.labels[std::size_t(s)]] -= volumeOf(s);
            moveNode(v, P(v) + bestStep * away[std::size_t(k)]);
            for (auto s : star_[std::size_t(v)]) volumeChange[m_.labels[std::size_t(s)]] += volumeOf(s);
            pushed_.insert(v);
            ++st.interfacePushes;
            st.largestPushMm = std::max(st.largestPushMm, bestStep);
            return true;
        }
        return false;
    }

    void compact() {
        TetMesh out;
        out.nodes = std::move(m_.nodes);
        for (std::size_t t = 0; t < m_.tets.size(); ++t)
            if (alive_[t]) {
                out.tets.push_back(m_.tets[t]);
                out.labels.push_back(m_.labels[t]);
            }
        m_ = std::move(out);
    }

private:
    const Vec3& P(std::int32_t v) const { return m_.nodes[std::size_t(v)]; }

    double volumeOf(std::int32_t t) const {
        const Tet& e = m_.tets[std::size_t(t)];
        return signedTetVolume(P(e[0]), P(e[1]), P(e[2]), P(e[3]));
    }

    /// Whether v lies on the mesh's outer boundary (a face of a tet around it has no tet across).
    bool onMeshBoundary(std::int32_t v) const {
        for (auto t : star_[std::size_t(v)]) {
            const Tet& e = m_.tets[std::size_t(t)];
            for (int k = 0; k < 4; ++k) {
                if (e[std::size_t(k)] == v) continue;
                std::int32_t f[3];
                if (acrossFace(t, k, f) < 0) return true;
            }
        }
        return false;
    }

    /// Whether an operation makes a candidate whose tets score `after` in place of `before`:
    /// when it raises them, or in a lookahead only the forced (k-th valid) candidate, which may
    /// lower them but makes no tet flatter than 1 degree (or than the worst it replaces): a
    /// nearly flat tet's orientation is at the mercy of rounding, and the operations after it
    /// rely on it.
    bool accepts(const Objective& after, const Objective& before) {
        if (forcedCandidate_ < 0) return after.betterThan(before);
        static const double floor = -std::cos(M_PI / 180.0);
        return after.worst > std::min(before.worst, floor) && candidatesSeen_++ == forcedCandidate_;
    }

    /// Whether the tets `fresh` fill exactly the volume of the tets `old` (a re-triangulation of
    /// the same cavity; with nearly flat tets around, positive orientation alone does not prove it).
    bool fillsSameVolume(const std::vector<std::int32_t>& old, const std::vector<Tet>& fresh) const {
        double volOld = 0, volNew = 0;
        for (auto t : old) {
            const Tet& e = m_.tets[std::size_t(t)];
            volOld += signedVolume6(P(e[0]), P(e[1]), P(e[2]), P(e[3]));
        }
        for (const Tet& e : fresh) volNew += signedVolume6(P(e[0]), P(e[1]), P(e[2]), P(e[3]));
        return std::abs(volNew - volOld) <= 1e-9 * volOld;
    }

    void moveNode(std::int32_t v, const Vec3& p) {
        for (auto t : star_[std::size_t(v)]) recordOriginal(t);
        for (Trial& trial : trials_) trial.moves.emplace_back(v, P(v));
        m_.nodes[std::size_t(v)] = p;
    }

    /// For every open trial: remembers the score of a tet that existed before it, the first time
    /// it changes.
    void recordOriginal(std::int32_t t) {
        for (Trial& trial : trials_) {
            if (std::size_t(t) >= trial.tets) continue;
            bool seen = false;
            for (const auto& o : trial.originals) seen = seen || o.first == t;
            if (!seen) trial.originals.emplace_back(t, tetScore(t));
        }
    }

    /// Lookahead trials made so far, and where they stop (deterministic: a count, not a clock).
    std::size_t trialsMade_ = 0;
    std::size_t trialLimit_ = std::numeric_limits<std::size_t>::max();

    void beginTrial() { trials_.push_back({m_.tets.size(), m_.nodes.size(), {}, {}}); }

    /// Closes the innermost trial keeping what it did (the enclosing trials still know it).
    void keepTrial() { trials_.pop_back(); }

    /// Closes the innermost trial restoring the mesh as it was at its beginTrial.
    void undoTrial() {
        const Trial& trial = trials_.back();
        for (std::size_t t = trial.tets; t < m_.tets.size(); ++t)
            if (alive_[t])
                for (auto v : m_.tets[t]) {
                    auto& s = star_[std::size_t(v)];
                    s.erase(std::find(s.begin(), s.end(), std::int32_t(t)));
                }
        m_.tets.resize(trial.tets);
        m_.labels.resize(trial.tets);
        alive_.resize(trial.tets);
        for (auto it = trial.originals.rbegin(); it != trial.originals.rend(); ++it)
            if (!alive_[std::size_t(it->first)]) {
                alive_[std::size_t(it->first)] = 1;
                for (auto v : m_.tets[std::size_t(it->first)]) star_[std::size_t(v)].push_back(it->first);
            }
        for (auto it = trial.moves.rbegin(); it != trial.moves.rend(); ++it) m_.nodes[std::size_t(it->first)] = it->second;
        m_.nodes.resize(trial.nodes);
        star_.resize(trial.nodes);
        fixed_.resize(trial.nodes);
        trials_.pop_back();
    }

    /// Hill climbing on the bad tets that share a node with a tet the trial made or moved.
    void improveAround(int depth, SliverStats& st) {
        for (int round = 0; round < 4; ++round) {
            const Trial& trial = trials_.back();
            std::vector<std::int32_t> nodes;
            for (std::size_t t = trial.tets; t < m_.tets.size(); ++t)
                if (alive_[t]) nodes.insert(nodes.end(), m_.tets[t].begin(), m_.tets[t].end());
            for (const auto& mv : trial.moves) nodes.push_back(mv.first);
            std::sort(nodes.begin(), nodes.end());
            nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
            std::vector<std::pair<double, std::int32_t>> bad;
            for (auto v : nodes)
                for (auto s : star_[std::size_t(v)]) {
                    const double q = tetScore(s);
                    if (q < target_) bad.emplace_back(q, s);
                }
            std::sort(bad.begin(), bad.end());
            bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
            bool changed = false;
            for (const auto& b : bad) changed |= improve(b.second, st) || (depth > 0 && improveWithLookahead(b.second, depth, st));
            if (!changed) return;
        }
    }

    /// Whether the trial left fewer tets under the target among those it changed without a worse
    /// worst, or as many with a better worst or a smaller shortfall.
    bool trialHelped() const {
        const Trial& trial = trials_.back();
        std::size_t badBefore = 0, badAfter = 0;
        Objective before, after;
        for (const auto& [t, q] : trial.originals) {
            badBefore += q < target_;
            before.add(q, target_);
            if (!alive_[std::size_t(t)]) continue;
            const double now = tetScore(t);
            badAfter += now < target_;
            after.add(now, target_);
        }
        for (std::size_t t = trial.tets; t < m_.tets.size(); ++t)
            if (alive_[t]) {
                const double now = tetScore(std::int32_t(t));
                badAfter += now < target_;
                after.add(now, target_);
            }
        if (badAfter < badBefore) return after.worst >= before.worst - 1e-12;
        return badAfter == badBefore && (after.worst > before.worst + 1e-9 || after.betterThan(before));
    }

    Objective objectiveOf(const std::vector<std::int32_t>& tets) const {
        Objective o;
        for (auto t : tets) o.add(tetScore(t), target_);
        return o;
    }

    /// The objective of the tets `tets` (by vertices) with vertex v placed at p.
    Objective scoreWith(const std::vector<Tet>& tets, std::int32_t v, const Vec3& p) const {
        Objective o;
        for (const Tet& e : tets) {
            const Vec3* q[4];
            for (int k = 0; k < 4; ++k) q[k] = e[std::size_t(k)] == v ? &p : &m_.nodes[std::size_t(e[std::size_t(k)])];
            o.add(score(*q[0], *q[1], *q[2], *q[3]), target_);
            if (o.worst <= kInvalid) break;
        }
        return o;
    }

    /// Pattern search for the position of v with the best objective over `tets`; returns that
    /// position and objective (the start's if nothing is better).
    std::pair<Vec3, Objective> bestPosition(const std::vector<Tet>& tets, std::int32_t v, Vec3 start) const {
        Objective best = scoreWith(tets, v, start);
        double shortest = std::numeric_limits<double>::infinity();
        for (const Tet& e : tets)
            for (auto w : e)
                if (w != v) shortest = std::min(shortest, (P(w) - start).norm());
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
                for (std::size_t k = r.begin(); k != r.end(); ++k) trialScore[k] = scoreWith(tets, v, trial[k]);
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

    /// bestPosition for a new vertex m from two starts: where it was put (on the split edge or
    /// face, where a flat sliver keeps its new tets flat) and the centroid of the replaced tets
    /// (off that plane).
    std::pair<Vec3, Objective> bestOfStarts(const std::vector<Tet>& fresh, std::int32_t m, const std::vector<std::int32_t>& old) const {
        Vec3 centroid = Vec3::Zero();
        for (auto t : old)
            for (auto v : m_.tets[std::size_t(t)]) centroid += P(v);
        centroid /= double(4 * old.size());
        auto first = bestPosition(fresh, m, P(m));
        auto second = bestPosition(fresh, m, centroid);
        return second.second.betterThan(first.second) ? second : first;
    }

    bool smooth(std::int32_t v) {
        std::vector<Tet> tets;
        for (auto t : star_[std::size_t(v)]) tets.push_back(m_.tets[std::size_t(t)]);
        const Objective before = scoreWith(tets, v, P(v));
        const auto [p, after] = bestPosition(tets, v, P(v));
        if (!after.betterThan(before)) return false;
        moveNode(v, p);
        return true;
    }

    std::vector<std::int32_t> tetsWith(std::int32_t a, std::int32_t b) const {
        std::vector<std::int32_t> out;
        for (auto t : star_[std::size_t(a)]) {
            const Tet& e = m_.tets[std::size_t(t)];
            if (std::find(e.begin(), e.end(), b) != e.end()) out.push_back(t);
        }
        return out;
    }

    void kill(std::int32_t t) {
        recordOriginal(t);
        alive_[std::size_t(t)] = 0;
        for (auto v : m_.tets[std::size_t(t)]) {
            auto& s = star_[std::size_t(v)];
            s.erase(std::find(s.begin(), s.end(), t));
        }
    }

    void add(const Tet& e, Label label) {
        const auto t = std::int32_t(m_.tets.size());
        m_.tets.push_back(e);
        m_.labels.push_back(label);
        alive_.push_back(1);
        for (auto v : e) star_[std::size_t(v)].push_back(t);
    }

    /// Replaces `old` by `fresh` (same label) when every new tet is positive, the volume is the
    /// same and the smallest score rises.
    bool replaceIfBetter(const std::vector<std::int32_t>& old, std::vector<Tet> fresh) {
        Objective sNew;
        for (Tet& e : fresh) {
            if (signedVolume6(P(e[0]), P(e[1]), P(e[2]), P(e[3])) < 0) std::swap(e[2], e[3]);
            sNew.add(score(P(e[0]), P(e[1]), P(e[2]), P(e[3])), target_);
        }
        if (!fillsSameVolume(old, fresh)) return false;  // not a re-triangulation of the same volume
        if (!accepts(sNew, objectiveOf(old))) return false;
        const Label label = m_.labels[std::size_t(old[0])];
        for (auto t : old) kill(t);
        for (const Tet& e : fresh) add(e, label);
        return true;
    }

    /// Face k of t (the three nodes other than t[k]) and the tet on its other side when that tet
    /// has t's label (-1 otherwise: an interface, the outside).
    std::int32_t sameRegionNeighbour(std::int32_t t, int k, std::int32_t f[3]) const {
        const std::int32_t s = acrossFace(t, k, f);
        return s >= 0 && m_.labels[std::size_t(s)] == m_.labels[std::size_t(t)] ? s : -1;
    }

    /// Face k of t (the three nodes other than t[k]) and the tet on its other side, whatever its
    /// label (-1: the mesh boundary).
    std::int32_t acrossFace(std::int32_t t, int k, std::int32_t f[3]) const {
        const Tet& e = m_.tets[std::size_t(t)];
        int n = 0;
        for (int j = 0; j < 4; ++j)
            if (j != k) f[n++] = e[std::size_t(j)];
        for (auto s : star_[std::size_t(f[0])]) {
            if (s == t) continue;
            const Tet& g = m_.tets[std::size_t(s)];
            if (std::find(g.begin(), g.end(), f[1]) != g.end() && std::find(g.begin(), g.end(), f[2]) != g.end()) return s;
        }
        return -1;
    }

    /// 2-3 flip of a face of t whose other tet has the same label.
    bool flip23Around(std::int32_t t, SliverStats& st) {
        const Tet e = m_.tets[std::size_t(t)];
        for (int k = 0; k < 4; ++k) {
            const std::int32_t d = e[std::size_t(k)];
            std::int32_t f[3];
            const std::int32_t other = sameRegionNeighbour(t, k, f);
            if (other < 0) continue;
            std::int32_t apex = -1;
            for (auto v : m_.tets[std::size_t(other)])
                if (v != f[0] && v != f[1] && v != f[2]) apex = v;
            std::vector<Tet> fresh = {{f[0], f[1], d, apex}, {f[1], f[2], d, apex}, {f[2], f[0], d, apex}};
            if (replaceIfBetter({t, other}, fresh)) {
                ++st.flips23;
                return true;
            }
        }
        return false;
    }

    /// The ring of edge (a, b) when it lies inside one region: its tets (all of label `label`,
    /// every face around the edge shared by two of them); empty otherwise.
    std::vector<std::int32_t> interiorRing(std::int32_t a, std::int32_t b, Label label) const {
        std::vector<std::int32_t> ring = tetsWith(a, b);
        std::vector<std::int32_t> apexCount;  // each ring vertex must appear in exactly two ring tets
        for (auto t : ring) {
            if (m_.labels[std::size_t(t)] != label) return {};
            for (auto v : m_.tets[std::size_t(t)])
                if (v != a && v != b) apexCount.push_back(v);
        }
        std::sort(apexCount.begin(), apexCount.end());
        for (std::size_t i = 0; i < apexCount.size();) {
            std::size_t j = i;
            while (j < apexCount.size() && apexCount[j] == apexCount[i]) ++j;
            if (j - i != 2) return {};
            i = j;
        }
        return ring;
    }

    /// Edge removal (Shewchuk 2002): an edge of t inside t's region with 3..7 tets around it is
    /// replaced by the best triangulation of its ring polygon joined to the edge's two ends (the
    /// 3-tet case is the 3-2 flip).
    bool removeEdgeAround(std::int32_t t, SliverStats& st) {
        const Tet e = m_.tets[std::size_t(t)];
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
                std::int32_t a = e[std::size_t(i)], b = e[std::size_t(j)];
                const std::vector<std::int32_t> ring = interiorRing(a, b, m_.labels[std::size_t(t)]);
                if (ring.size() < 3 || ring.size() > 7) continue;
                std::vector<std::int32_t> r = ringPolygon(a, b, ring);
                if (r.size() != ring.size()) continue;
                const std::vector<Tet> fresh = bestRingTriangulation(a, b, r);
                if (fresh.empty()) continue;
                if (replaceIfBetter(ring, fresh)) {
                    ++(ring.size() == 3 ? st.flips32 : st.edgeRemovals);
                    return true;
                }
            }
        return false;
    }

    /// The ring vertices of edge (a, b) in cyclic order, oriented so (a, b, r[k], r[k+1]) is positive.
    std::vector<std::int32_t> ringPolygon(std::int32_t a, std::int32_t b, const std::vector<std::int32_t>& ring) const {
        std::vector<std::pair<std::int32_t, std::int32_t>> links;
        for (auto s : ring) {
            std::int32_t x[2], n = 0;
            for (auto v : m_.tets[std::size_t(s)])
                if (v != a && v != b) x[n++] = v;
            links.emplace_back(x[0], x[1]);
        }
        std::vector<std::int32_t> r = {links[0].first, links[0].second};
        std::vector<char> used(links.size(), 0);
        used[0] = 1;
        while (r.size() < links.size()) {
            bool found = false;
            for (std::size_t k = 0; k < links.size() && !found; ++k) {
                if (used[k]) continue;
                if (links[k].first == r.back()) r.push_back(links[k].second), found = true;
                else if (links[k].second == r.back()) r.push_back(links[k].first), found = true;
                if (found) used[k] = 1;
            }
            if (!found) return {};
        }
        if (signedVolume6(P(a), P(b), P(r[0]), P(r[1])) < 0) std::reverse(r.begin(), r.end());
        return r;
    }

    /// Triangulation of the ring polygon maximising the smallest score of the tets it makes with
    /// a (below) and b (above); empty when some triangle would give an inverted tet.
    std::vector<Tet> bestRingTriangulation(std::int32_t a, std::int32_t b, const std::vector<std::int32_t>& r) const {
        const int n = int(r.size());
        constexpr double kNone = -std::numeric_limits<double>::infinity();
        std::vector<double> q(std::size_t(n * n), kNone);
        std::vector<int> split(std::size_t(n * n), -1);
        const auto at = [n](int i, int j) { return std::size_t(i * n + j); };
        for (int i = 0; i + 1 < n; ++i) q[at(i, i + 1)] = std::numeric_limits<double>::infinity();
        for (int len = 2; len < n; ++len)
            for (int i = 0; i + len < n; ++i) {
                const int j = i + len;
                for (int k = i + 1; k < j; ++k) {
                    const double s = std::min({q[at(i, k)], q[at(k, j)], score(P(r[std::size_t(i)]), P(r[std::size_t(k)]), P(r[std::size_t(j)]), P(b)),
                                               score(P(r[std::size_t(i)]), P(r[std::size_t(j)]), P(r[std::size_t(k)]), P(a))});
                    if (s > q[at(i, j)]) {
                        q[at(i, j)] = s;
                        split[at(i, j)] = k;
                    }
                }
            }
        if (!(q[at(0, n - 1)] > kInvalid)) return {};
        std::vector<Tet> out;
        std::vector<std::pair<int, int>> todo = {{0, n - 1}};
        while (!todo.empty()) {
            const auto [i, j] = todo.back();
            todo.pop_back();
            if (j - i < 2) continue;
            const int k = split[at(i, j)];
            out.push_back({r[std::size_t(i)], r[std::size_t(k)], r[std::size_t(j)], b});
            out.push_back({r[std::size_t(i)], r[std::size_t(j)], r[std::size_t(k)], a});
            todo.push_back({i, k});
            todo.push_back({k, j});
        }
        return out;
    }

    /// Splits an edge of t that lies inside t's region (longest first) and smooths the new vertex.
    bool splitAround(std::int32_t t, SliverStats& st) {
        const Tet e = m_.tets[std::size_t(t)];
        std::vector<std::pair<double, std::pair<std::int32_t, std::int32_t>>> edges;
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
                const std::int32_t a = e[std::size_t(i)], b = e[std::size_t(j)];
                edges.push_back({-(P(a) - P(b)).squaredNorm(), {std::min(a, b), std::max(a, b)}});
            }
        std::sort(edges.begin(), edges.end());
        for (const auto& [negLen, ab] : edges) {
            const auto [a, b] = ab;
            const std::vector<std::int32_t> ring = interiorRing(a, b, m_.labels[std::size_t(t)]);
            if (ring.empty()) continue;
            const auto m = std::int32_t(m_.nodes.size());  // the new vertex (not yet added)
            std::vector<Tet> fresh;
            for (auto s : ring) {
                Tet x = m_.tets[std::size_t(s)], y = x;
                for (auto& v : x)
                    if (v == a) v = m;
                for (auto& v : y)
                    if (v == b) v = m;
                fresh.push_back(x);
                fresh.push_back(y);
            }
            m_.nodes.push_back(0.5 * (P(a) + P(b)));
            const auto [p, after] = bestOfStarts(fresh, m, ring);
            m_.nodes.back() = p;
            if (!accepts(after, objectiveOf(ring)) || !fillsSameVolume(ring, fresh)) {
                m_.nodes.pop_back();
                continue;
            }
            commitNewVertex(ring, fresh, m_.labels[std::size_t(t)]);
            ++st.splits;
            return true;
        }
        return false;
    }

    /// Adds vertex m at p (already in nodes) with the tets `fresh` in place of `old`.
    void commitNewVertex(const std::vector<std::int32_t>& old, const std::vector<Tet>& fresh, Label label) {
        star_.emplace_back();
        fixed_.push_back(0);
        for (auto s : old) kill(s);
        for (const Tet& x : fresh) add(x, label);
    }

    /// Splits a face of t shared with a tet of the same label at a new vertex, which is then
    /// smoothed (it can leave the face: its star is the six new tets).
    bool splitFaceAround(std::int32_t t, SliverStats& st) {
        const Label label = m_.labels[std::size_t(t)];
        for (int k = 0; k < 4; ++k) {
            std::int32_t f[3];
            const std::int32_t other = sameRegionNeighbour(t, k, f);
            if (other < 0) continue;
            const auto m = std::int32_t(m_.nodes.size());
            std::vector<Tet> fresh;
            for (auto s : {t, other}) {
                const Tet g = m_.tets[std::size_t(s)];
                for (int i = 0; i < 4; ++i) {  // replace each face vertex by m in turn: orientation kept
                    if (std::find(f, f + 3, g[std::size_t(i)]) == f + 3) continue;
                    Tet x = g;
                    x[std::size_t(i)] = m;
                    fresh.push_back(x);
                }
            }
            m_.nodes.push_back((P(f[0]) + P(f[1]) + P(f[2])) / 3.0);
            const auto [p, after] = bestOfStarts(fresh, m, {t, other});
            m_.nodes.back() = p;
            if (!accepts(after, objectiveOf({t, other})) || !fillsSameVolume({t, other}, fresh)) {
                m_.nodes.pop_back();
                continue;
            }
            commitNewVertex({t, other}, fresh, label);
            ++st.faceSplits;
            return true;
        }
        return false;
    }

    /// Inserts a vertex near t, Bowyer-Watson style inside t's region: the tets of the region
    /// connected to t whose circumsphere holds the new vertex are replaced by its star over their
    /// outer faces. This is what a flat tet lying on two boundary faces at a ridge needs: a vertex
    /// above the ridge, which no split of a single edge or face can reach. Starts: t's centroid and
    /// points above each of t's boundary edges shared by two boundary faces.
    bool starCavityAround(std::int32_t t, SliverStats& st) {
        const Tet e = m_.tets[std::size_t(t)];
        std::vector<Vec3> starts;
        starts.push_back(0.25 * (P(e[0]) + P(e[1]) + P(e[2]) + P(e[3])));
        // Faces of t on the region's boundary, with their normals pointing out of t.
        std::vector<std::pair<int, Vec3>> boundary;
        for (int k = 0; k < 4; ++k) {
            std::int32_t f[3];
            if (sameRegionNeighbour(t, k, f) >= 0) continue;
            const Vec3 n = (P(f[1]) - P(f[0])).cross(P(f[2]) - P(f[0]));
            const Vec3 out = (P(f[0]) - P(e[std::size_t(k)])).dot(n) > 0 ? n : Vec3(-n);
            boundary.emplace_back(k, out.normalized());
        }
        // On a region-boundary face: where the apex of a regular tet on that face would be, and
        // lower (a tet with one boundary face is best mended by a vertex above that face).
        for (const auto& [k, out] : boundary) {
            const Vec3& a = P(e[std::size_t((k + 1) % 4)]);
            const Vec3& b = P(e[std::size_t((k + 2) % 4)]);
            const Vec3& c = P(e[std::size_t((k + 3) % 4)]);
            const double meanEdge = ((a - b).norm() + (b - c).norm() + (c - a).norm()) / 3.0;
            const double regularHeight = std::sqrt(2.0 / 3.0) * meanEdge;
            for (double h : {1.0, 0.7, 0.45}) starts.push_back((a + b + c) / 3.0 - h * regularHeight * out);
        }
        for (std::size_t i = 0; i < boundary.size(); ++i)
            for (std::size_t j = i + 1; j < boundary.size(); ++j) {
                // the edge shared by the faces opposite vertices k1 and k2: the other two vertices
                const int k1 = boundary[i].first, k2 = boundary[j].first;
                Vec3 a = Vec3::Zero();
                for (int v = 0; v < 4; ++v)
                    if (v != k1 && v != k2) a += 0.5 * P(e[std::size_t(v)]);
                const Vec3 in = -(boundary[i].second + boundary[j].second).normalized();
                const double len = (P(e[std::size_t(k1)]) - P(e[std::size_t(k2)])).norm();
                for (double h : {0.15, 0.3, 0.45, 0.6, 0.9}) starts.push_back(a + h * len * in);
            }
        for (const Vec3& q : starts) {
            std::vector<std::int32_t> cavity = circumsphereCavity(t, q);
            if (!growUntilStarShaped(cavity, q)) continue;
            std::vector<Tet> tets = starOfCavity(cavity);
            const auto m = std::int32_t(m_.nodes.size());
            m_.nodes.push_back(q);
            for (Tet& x : tets)
                for (auto& v : x)
                    if (v < 0) v = m;
            const auto [p, after] = bestPosition(tets, m, q);
            m_.nodes.back() = p;
            if (!accepts(after, objectiveOf(cavity)) || !fillsSameVolume(cavity, tets)) {
                m_.nodes.pop_back();
                continue;
            }
            commitNewVertex(cavity, tets, m_.labels[std::size_t(t)]);
            ++st.cavityStars;
            return true;
        }
        return false;
    }

    /// Inserts a vertex on an interface next to t: on one of t's faces or edges that lie on an
    /// interface (or the mesh boundary), so the surface keeps its geometry (the point is on the
    /// triangle or segment) and both sides keep sharing their faces. Every region around the
    /// point gets a Bowyer-Watson cavity grown from the tets that hold the point, starred from it
    /// over the cavity's outer faces except those the point lies on (their cones are flat; the
    /// split interface triangles come out as the new faces through the point). This is the one
    /// operation that can mend a sliver wedged between two close interfaces (a PDL one tet thick)
    /// or with all four nodes on them: TetGen under -Y may not put a node there itself.
    /// Candidates: the centroid of each interface face of t and the projection of t's opposite
    /// node on it (when inside), the midpoint of each interface edge and its point closest to the
    /// opposite edge. The best candidate is made when it improves the objective over the tets it
    /// replaces.
    bool insertOnInterfaceAround(std::int32_t t, SliverStats& st) {
        const Tet e = m_.tets[std::size_t(t)];
        struct Candidate {
            Vec3 q;
            std::vector<std::int32_t> holders;  // tets whose closure holds q
            std::array<std::int32_t, 3> carrier;  // the face (or edge: carrier[2] = -1) q lies on
        };
        std::vector<Candidate> candidates;
        for (int k = 0; k < 4; ++k) {
            std::int32_t f[3];
            const std::int32_t other = acrossFace(t, k, f);
            if (other >= 0 && m_.labels[std::size_t(other)] == m_.labels[std::size_t(t)]) continue;
            std::vector<std::int32_t> holders{t};
            if (other >= 0) holders.push_back(other);
            std::array<std::int32_t, 3> key{f[0], f[1], f[2]};
            std::sort(key.begin(), key.end());
            const Vec3 &a = P(f[0]), &b = P(f[1]), &c = P(f[2]);
            candidates.push_back({(a + b + c) / 3.0, holders, key});
            // the opposite node's foot on the face, when strictly inside it
            const Vec3 n = (b - a).cross(c - a);
            const double n2 = n.squaredNorm();
            if (!(n2 > 0)) continue;
            const Vec3 foot = P(e[std::size_t(k)]) - n * (n.dot(P(e[std::size_t(k)]) - a) / n2);
            const double wa = n.dot((b - foot).cross(c - foot)) / n2, wb = n.dot((c - foot).cross(a - foot)) / n2;
            const double wc = 1.0 - wa - wb;
            if (std::min({wa, wb, wc}) > 0.1) candidates.push_back({wa * a + wb * b + wc * c, holders, key});
        }
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
                const std::int32_t a = e[std::size_t(i)], b = e[std::size_t(j)];
                if (!interiorRing(a, b, m_.labels[std::size_t(t)]).empty()) continue;  // not on an interface
                const std::vector<std::int32_t> ring = tetsWith(a, b);
                std::array<std::int32_t, 3> key{std::min(a, b), std::max(a, b), -1};
                candidates.push_back({0.5 * (P(a) + P(b)), ring, key});
                // the point of a-b closest to the opposite edge c-d
                std::int32_t cd[2], n = 0;
                for (auto v : e)
                    if (v != a && v != b) cd[n++] = v;
                const Vec3 u = P(b) - P(a), w = P(cd[1]) - P(cd[0]), r = P(a) - P(cd[0]);
                const double uu = u.dot(u), uw = u.dot(w), ww = w.dot(w), ur = u.dot(r), wr = w.dot(r);
                const double den = uu * ww - uw * uw;
                if (!(den > 1e-12 * uu * ww)) continue;
                const double s = (uw * wr - ww * ur) / den;
                if (s > 0.15 && s < 0.85 && std::abs(s - 0.5) > 0.05) candidates.push_back({P(a) + s * u, ring, key});
            }

        struct Best {
            Objective objective;
            Vec3 q;
            std::vector<std::int32_t> old;
            std::vector<std::pair<Tet, Label>> fresh;
        } best;
        bool found = false;
        for (const Candidate& c : candidates) {
            const bool onFace = c.carrier[2] >= 0;
            const FaceFilter skip = [&](const std::array<std::int32_t, 3>& face) {
                if (onFace) return face == c.carrier;
                return std::binary_search(face.begin(), face.end(), c.carrier[0]) &&
                       std::binary_search(face.begin(), face.end(), c.carrier[1]);
            };
            std::vector<std::int32_t> old;
            std::vector<std::pair<Tet, Label>> fresh;
            Objective after;
            bool ok = true;
            std::vector<Label> labels;
            for (auto h : c.holders) labels.push_back(m_.labels[std::size_t(h)]);
            std::sort(labels.begin(), labels.end());
            labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
            for (Label label : labels) {
                std::vector<std::int32_t> cavity;
                for (auto h : c.holders)
                    if (m_.labels[std::size_t(h)] == label) cavity.push_back(h);
                growCircumsphereCavity(cavity, c.q);
                if (!growUntilStarShaped(cavity, c.q, skip)) {
                    ok = false;
                    break;
                }
                double volOld = 0, volNew = 0;
                for (auto x : cavity) {
                    const Tet& g = m_.tets[std::size_t(x)];
                    volOld += signedVolume6(P(g[0]), P(g[1]), P(g[2]), P(g[3]));
                }
                for (Tet x : starOfCavity(cavity, skip)) {
                    const Vec3* p[4];
                    for (int k = 0; k < 4; ++k) p[k] = x[std::size_t(k)] < 0 ? &c.q : &P(x[std::size_t(k)]);
                    const double s6 = score(*p[0], *p[1], *p[2], *p[3]);
                    volNew += signedVolume6(*p[0], *p[1], *p[2], *p[3]);
                    after.add(s6, target_);
                    fresh.emplace_back(x, label);
                }
                // the star fills exactly the cavity (no face of it missed or counted twice)
                if (std::abs(volNew - volOld) > 1e-9 * volOld) {
                    ok = false;
                    break;
                }
                old.insert(old.end(), cavity.begin(), cavity.end());
            }
            if (!ok || after.worst <= kInvalid || !accepts(after, objectiveOf(old))) continue;
            if (!found || after.betterThan(best.objective)) {
                best = {after, c.q, old, fresh};
                found = true;
            }
        }
        if (!found) return false;
        const auto m = std::int32_t(m_.nodes.size());
        m_.nodes.push_back(best.q);
        star_.emplace_back();
        fixed_.push_back(1);  // on an interface: it never moves
        for (auto x : best.old) kill(x);
        for (auto& [x, label] : best.fresh) {
            for (auto& v : x)
                if (v < 0) v = m;
            add(x, label);
        }
        ++st.interfaceInsertions;
        return true;
    }

    /// Adds to `cavity` (tets of one region) the tets of that region connected to it through
    /// faces whose circumsphere holds q (at most 64 tets in all).
    void growCircumsphereCavity(std::vector<std::int32_t>& cavity, const Vec3& q) const {
        for (std::size_t i = 0; i < cavity.size() && cavity.size() < 64; ++i)
            for (int k = 0; k < 4; ++k) {
                std::int32_t f[3];
                const std::int32_t s = sameRegionNeighbour(cavity[i], k, f);
                if (s < 0 || std::find(cavity.begin(), cavity.end(), s) != cavity.end()) continue;
                const Tet& g = m_.tets[std::size_t(s)];
                if (insideCircumsphere(P(g[0]), P(g[1]), P(g[2]), P(g[3]), q)) cavity.push_back(s);
            }
    }

    /// t and the tets of its region connected to it through faces whose circumsphere holds q
    /// (at most 64 tets).
    std::vector<std::int32_t> circumsphereCavity(std::int32_t t, const Vec3& q) const {
        std::vector<std::int32_t> cavity{t};
        growCircumsphereCavity(cavity, q);
        return cavity;
    }

    /// Adds to `cavity` the region's tets behind every outer face that q does not see from inside,
    /// until q sees them all (true) or such a face is on the region's boundary or the cavity grows
    /// past 64 tets (false). TetGen's output is not Delaunay after improvement, so the
    /// circumsphere cavity alone is not always star-shaped.
    bool growUntilStarShaped(std::vector<std::int32_t>& cavity, const Vec3& q, const FaceFilter& skip = {}) const {
        while (cavity.size() <= 64) {
            bool grown = false;
            const std::vector<Tet> star = starOfCavity(cavity, skip);
            for (const Tet& x : star) {
                const Vec3* p[4];
                int hole = 0;
                for (int k = 0; k < 4; ++k) {
                    if (x[std::size_t(k)] < 0) hole = k;
                    p[k] = x[std::size_t(k)] < 0 ? &q : &P(x[std::size_t(k)]);
                }
                if (signedVolume6(*p[0], *p[1], *p[2], *p[3]) > 0) continue;
                // the cavity tet this face belongs to, and the tet behind the face
                std::int32_t f[3];
                int n = 0;
                for (int k = 0; k < 4; ++k)
                    if (k != hole) f[n++] = x[std::size_t(k)];
                std::int32_t behind = -1;
                for (auto c : cavity) {
                    const Tet& g = m_.tets[std::size_t(c)];
                    int opposite = -1, shared = 0;
                    for (int k = 0; k < 4; ++k) {
                        if (std::find(f, f + 3, g[std::size_t(k)]) != f + 3) ++shared;
                        else opposite = k;
                    }
                    if (shared != 3) continue;
                    std::int32_t face[3];
                    behind = sameRegionNeighbour(c, opposite, face);
                    break;
                }
                if (behind < 0) return false;
                if (std::find(cavity.begin(), cavity.end(), behind) == cavity.end()) {
                    cavity.push_back(behind);
                    grown = true;
                    break;
                }
            }
            if (!grown) return true;
        }
        return false;
    }

    /// The outer faces of `cavity` (faces of one of its tets only), each as its tet with the
    /// opposite vertex replaced by -1: orientation kept, so with a new vertex there every tet is
    /// positive exactly when that vertex sees the face from inside.
    std::vector<Tet> starOfCavity(const std::vector<std::int32_t>& cavity, const FaceFilter& skip = {}) const {
        std::vector<std::array<std::int32_t, 3>> keys;
        for (auto c : cavity)
            for (int i = 0; i < 4; ++i) {
                std::array<std::int32_t, 3> key{};
                int n = 0;
                for (int j = 0; j < 4; ++j)
                    if (j != i) key[std::size_t(n++)] = m_.tets[std::size_t(c)][std::size_t(j)];
                std::sort(key.begin(), key.end());
                keys.push_back(key);
            }
        std::vector<Tet> star;
        for (std::size_t ci = 0; ci < cavity.size(); ++ci)
            for (int i = 0; i < 4; ++i) {
                if (std::count(keys.begin(), keys.end(), keys[4 * ci + std::size_t(i)]) > 1) continue;
                if (skip && skip(keys[4 * ci + std::size_t(i)])) continue;
                Tet x = m_.tets[std::size_t(cavity[ci])];
                x[std::size_t(i)] = -1;
                star.push_back(x);
            }
        return star;
    }

    TetMesh& m_;
    double target_;
    bool interfaceInsertions_;
    std::vector<char> alive_, fixed_;
    std::set<std::int32_t> pushed_;  ///< interface nodes pushed once already
    std::vector<std::vector<std::int32_t>> star_;
    // Lookahead: the candidate an operation must make (-1: only one that helps), candidates seen.
    int forcedCandidate_ = -1, candidatesSeen_ = 0;
    // Open lookahead trials, innermost last: sizes at the start, tets changed (score before),
    // nodes moved (position before).
    struct Trial {
        std::size_t tets, nodes;
        std::vector<std::pair<std::int32_t, double>> originals;
        std::vector<std::pair<std::int32_t, Vec3>> moves;
    };
    std::vector<Trial> trials_;
};

/// Smallest dihedral angle of the mesh and the number of tets below the target.
std::pair<double, std::size_t> worstAndBad(const TetMesh& mesh, double targetDeg) {
    double worst = std::numeric_limits<double>::infinity();
    std::size_t bad = 0;
    for (const Tet& e : mesh.tets) {
        const double deg = scoreToDeg(score(mesh.nodes[std::size_t(e[0])], mesh.nodes[std::size_t(e[1])],
                                            mesh.nodes[std::size_t(e[2])], mesh.nodes[std::size_t(e[3])]));
        worst = std::min(worst, deg);
        if (deg < targetDeg) ++bad;
    }
    return {mesh.tets.empty() ? 0.0 : worst, bad};
}

}  // namespace

void improveSlivers(TetMesh& mesh, const SliverOptions& options, SliverStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    SliverStats st;
    std::tie(st.minDihedralBeforeDeg, st.badBefore) = worstAndBad(mesh, options.targetMinDihedralDeg);
    const std::map<Label, double> volumesBefore = st.badBefore > 0 ? labelVolumesMm3(mesh) : std::map<Label, double>{};
    if (st.badBefore > 0) {
        SliverImprover imp(mesh, options);
        std::vector<std::int32_t> bad = imp.badTets();
        for (int pass = 0; pass < options.maxPasses && !bad.empty(); ++pass) {
            ++st.passes;
            bool changed = false;
            for (auto t : bad) changed |= imp.improve(t, st);
            bad = imp.badTets();
            if (!changed) break;
        }
        // Iterative deepening: depth 2 only where depth 1 is stuck.
        const auto deepen = [&](int fromDepth, int toDepth) {
            for (int depth = fromDepth, pass = 0; depth <= toDepth && pass < options.maxPasses && !bad.empty(); ++pass) {
                ++st.passes;
                bool changed = false;
                for (auto t : bad) changed |= imp.improveWithLookahead(t, depth, st);
                bad = imp.badTets();
                if (!changed) ++depth;
            }
        };
        deepen(1, options.lookaheadDepth);
        // The last resort, then the usual operations again around what it moved.
        std::map<Label, double> pushedVolume;
        if (options.interfacePushMm > 0 && !bad.empty()) {
            bool changed = false;
            for (auto t : bad) changed |= imp.pushInterfaceNode(t, options.interfacePushMm, pushedVolume, st);
            for (int pass = 0; changed && pass < options.maxPasses; ++pass) {
                ++st.passes;
                changed = false;
                for (auto t : imp.badTets()) changed |= imp.improve(t, st);
            }
            bad = imp.badTets();
        }
        // Deeper lookaheads for the last few, each depth within its count of trials.
        if (options.lookaheadDepth > 0 && bad.size() <= options.deepLookaheadTets)
            for (int depth = options.lookaheadDepth + 1; depth <= options.deepLookaheadDepth && !bad.empty(); ++depth) {
                imp.limitTrials(options.deepLookaheadTrials);
                deepen(depth, depth);
            }
        imp.compact();
        // Every operation re-triangulates a cavity of one region (or splits an interface in
        // place; pushes move it by what they recorded): a region whose volume changed otherwise
        // means a bug, and a mesh not to hand on.
        for (const auto& [label, volume] : labelVolumesMm3(mesh))
            if (std::abs(volume - volumesBefore.at(label) - pushedVolume[label]) > 1e-9 * volumesBefore.at(label))
                throw Error("improveSlivers", "internal error: the volume of label " + std::to_string(label) + " changed from " +
                                                  std::to_string(volumesBefore.at(label)) + " to " + std::to_string(volume) + " mm^3");
    }
    std::tie(st.minDihedralAfterDeg, st.badAfter) = worstAndBad(mesh, options.targetMinDihedralDeg);
    st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (stats) *stats = st;
}

}  // namespace jawmesh
