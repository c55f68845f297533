// The sliver improver's driver (tet/ImproveSlivers.h): passes of hill climbing over the bad tets,
// the lookahead and its checkpoints, the last-resort pushes, the statistics and the final volume
// check. The operations themselves are tet/Sliver*.cpp over tet/TetMeshEditor.h.
#include "tet/ImproveSlivers.h"

#include "io/Error.h"
#include "io/ResourceUsage.h"
#include "tet/ElementQuality.h"
#include "tet/SliverCavity.h"
#include "tet/SliverFlips.h"
#include "tet/SliverInterfaceInsert.h"
#include "tet/SliverPush.h"
#include "tet/SliverScore.h"
#include "tet/SliverSmooth.h"
#include "tet/SliverSplits.h"
#include "tet/TetMeshEditor.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace jawmesh {
namespace {

/// An operation on a bad tet (tet/Sliver*.h): true when it made a candidate the rule accepted.
using Operation = bool (*)(TetMeshEditor&, std::int32_t, Acceptance&, SliverStats&);

/// The operations after smoothing, in the order they are tried (and the lookahead forces them).
constexpr Operation kOperations[] = {flip23Around,    removeEdgeAround, splitEdgeAround,
                                     splitFaceAround, starCavityAround, insertOnInterfaceAround};

/// What the passes share: the mesh being edited, the target score and the lookahead's trial count.
struct Improver {
    TetMeshEditor& mesh;
    double target;
    bool interfaceInsertions;
    /// Lookahead trials made so far, and where they stop (deterministic: a count, not a clock).
    std::size_t trialsMade = 0;
    std::size_t trialLimit = std::numeric_limits<std::size_t>::max();
    /// Every tet's score as badTets last saw it (stale only for tets the editor reports touched);
    /// empty before its first call.
    std::vector<double> scores{};
};

/// The bad tets, worst first (ties by index).
std::vector<std::int32_t> badTets(Improver& imp) {
    TetMeshEditor& mesh = imp.mesh;
    // All tets scored once, in parallel; later only those the editor touched since (a pass
    // changes a few thousand of the 600 k; scoring them all was a sixth of the improver).
    std::vector<double>& scores = imp.scores;
    std::vector<std::int32_t> touched = mesh.takeTouched();
    const bool first = scores.empty();
    scores.resize(mesh.tetCount(), kInvalidScore);
    if (first) {
        touched.resize(mesh.tetCount());
        std::iota(touched.begin(), touched.end(), 0);
    } else {
        std::sort(touched.begin(), touched.end());
        touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, touched.size(), 4096), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const std::int32_t t = touched[i];
            if (std::size_t(t) < mesh.tetCount() && mesh.alive(t)) scores[std::size_t(t)] = mesh.score(t);
        }
    });
    std::vector<std::pair<double, std::int32_t>> bad;
    for (std::size_t t = 0; t < mesh.tetCount(); ++t)
        if (mesh.alive(std::int32_t(t)) && scores[t] < imp.target) bad.emplace_back(scores[t], std::int32_t(t));
    std::sort(bad.begin(), bad.end());
    std::vector<std::int32_t> out;
    for (auto& b : bad) out.push_back(b.second);
    return out;
}

/// One attempt to improve tet t by hill climbing; true when something was changed.
bool improve(Improver& imp, std::int32_t t, SliverStats& st) {
    if (!imp.mesh.alive(t) || imp.mesh.score(t) >= imp.target) return false;
    Acceptance accept = Acceptance::improving(imp.target);
    if (smoothAround(imp.mesh, t, accept, st)) return true;
    for (Operation op : kOperations) {
        if (op == insertOnInterfaceAround && !imp.interfaceInsertions) continue;
        if (op(imp.mesh, t, accept, st)) return true;
    }
    return false;
}

bool improveWithLookahead(Improver& imp, std::int32_t t, int depth, SliverStats& st);

/// Hill climbing on the bad tets that share a node with a tet the innermost checkpoint made or
/// moved (with a lookahead of `depth` where that alone fails), up to 4 rounds.
void improveAround(Improver& imp, int depth, SliverStats& st) {
    const TetMeshEditor& mesh = imp.mesh;
    for (int round = 0; round < 4; ++round) {
        // read before the improvements below open checkpoints of their own (which may move it)
        const TetMeshEditor::Checkpoint& trial = mesh.innermost();
        std::vector<std::int32_t> nodes;
        for (std::size_t t = trial.firstNewTet; t < mesh.tetCount(); ++t)
            if (mesh.alive(std::int32_t(t))) {
                const Tet& e = mesh.tet(std::int32_t(t));
                nodes.insert(nodes.end(), e.begin(), e.end());
            }
        for (const auto& mv : trial.movedNodes) nodes.push_back(mv.first);
        std::sort(nodes.begin(), nodes.end());
        nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
        std::vector<std::pair<double, std::int32_t>> bad;
        for (auto v : nodes)
            for (auto s : mesh.star(v)) {
                const double q = mesh.score(s);
                if (q < imp.target) bad.emplace_back(q, s);
            }
        std::sort(bad.begin(), bad.end());
        bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
        bool changed = false;
        for (const auto& b : bad) changed |= improve(imp, b.second, st) || (depth > 0 && improveWithLookahead(imp, b.second, depth, st));
        if (!changed) return;
    }
}

/// Whether the innermost checkpoint's edits left fewer tets under the target among those they
/// changed without a worse worst, or as many with a better worst or a smaller shortfall.
bool trialHelped(const Improver& imp) {
    const TetMeshEditor& mesh = imp.mesh;
    const TetMeshEditor::Checkpoint& trial = mesh.innermost();
    std::size_t badBefore = 0, badAfter = 0;
    Objective before, after;
    for (const auto& [t, q] : trial.changedTets) {
        badBefore += q < imp.target;
        before.add(q, imp.target);
        if (!mesh.alive(t)) continue;
        const double now = mesh.score(t);
        badAfter += now < imp.target;
        after.add(now, imp.target);
    }
    for (std::size_t t = trial.firstNewTet; t < mesh.tetCount(); ++t)
        if (mesh.alive(std::int32_t(t))) {
            const double now = mesh.score(std::int32_t(t));
            badAfter += now < imp.target;
            after.add(now, imp.target);
        }
    if (badAfter < badBefore) return after.worst >= before.worst - 1e-12;
    return badAfter == badBefore && (after.worst > before.worst + 1e-9 || after.betterThan(before));
}

/// Lookahead, for a tet at a local optimum of the hill climbing (no single operation raises the
/// tets it changes): each candidate of each operation is made whether it helps or not (the rule
/// Acceptance::forced), the bad tets around what it made are then improved as usual (with a
/// lookahead of depth - 1 where that alone fails), and the whole is kept only when trialHelped;
/// otherwise it is undone. A flip or a split that first makes things worse can open the way to a
/// smoothing or another flip: the slivers a single step cannot mend.
bool improveWithLookahead(Improver& imp, std::int32_t t, int depth, SliverStats& st) {
    if (!imp.mesh.alive(t) || imp.mesh.score(t) >= imp.target) return false;
    for (Operation op : kOperations) {
        if (op == insertOnInterfaceAround && !imp.interfaceInsertions) continue;
        for (int k = 0;; ++k) {
            if (imp.trialsMade >= imp.trialLimit) return false;
            ++imp.trialsMade;
            SliverStats trial = st;
            imp.mesh.checkpoint();
            Acceptance forced = Acceptance::forced(imp.target, k);
            if (op(imp.mesh, t, forced, trial)) {
                improveAround(imp, depth - 1, trial);
                if (trialHelped(imp)) {
                    imp.mesh.keep();
                    st = trial;
                    ++st.lookaheads;
                    return true;
                }
            }
            imp.mesh.rollback();
            if (forced.candidatesSeen() <= k) break;  // the operation has no k-th candidate
        }
    }
    return false;
}

/// Smallest dihedral angle of the mesh and the number of tets below the target.
std::pair<double, std::size_t> worstAndBad(const TetMesh& mesh, double targetDeg) {
    double worst = std::numeric_limits<double>::infinity();
    std::size_t bad = 0;
    for (const Tet& e : mesh.tets) {
        const double deg = scoreToDeg(sliverScore(mesh.nodes[std::size_t(e[0])], mesh.nodes[std::size_t(e[1])],
                                                  mesh.nodes[std::size_t(e[2])], mesh.nodes[std::size_t(e[3])]));
        worst = std::min(worst, deg);
        if (deg < targetDeg) ++bad;
    }
    return {mesh.tets.empty() ? 0.0 : worst, bad};
}

/// Progress of one phase of the stage (passes of hill climbing, of lookahead, ...) as the part
/// [from, to) of its fraction, and the safe points where a cancel is honoured (between tets). How
/// many passes a phase takes is not known ahead: each pass fills half of what the earlier ones
/// left, in proportion to the tets it has done.
class PhaseProgress {
public:
    PhaseProgress(ProgressStage& stage, const Progress& progress, double from, double to)
        : stage_(stage), progress_(progress), from_(from), to_(to) {}
    /// Runs `step` on every tet of `tets` in order; true when one of them changed something.
    /// Throws Cancelled between tets when asked to stop.
    template <typename Step>
    bool pass(const std::vector<std::int32_t>& tets, Step&& step) {
        const double begin = 1.0 - std::ldexp(1.0, -passes_), end = 1.0 - std::ldexp(1.0, -(passes_ + 1));
        ++passes_;
        bool changed = false;
        for (std::size_t i = 0; i < tets.size(); ++i) {
            progress_.checkCancelled();
            if (i % 64 == 0) stage_.update(from_ + (to_ - from_) * (begin + (end - begin) * double(i) / double(tets.size())));
            changed |= step(tets[i]);
        }
        return changed;
    }

private:
    ProgressStage& stage_;
    const Progress& progress_;
    double from_, to_;
    int passes_ = 0;
};

}  // namespace

void improveSlivers(TetMesh& mesh, const SliverOptions& options, SliverStats* stats, Progress& progress) {
    ProgressStage stage(progress, "improve slivers");
    const auto start = std::chrono::steady_clock::now();
    SliverStats st;
    std::tie(st.minDihedralBeforeDeg, st.badBefore) = worstAndBad(mesh, options.targetMinDihedralDeg);
    const std::map<Label, double> volumesBefore = st.badBefore > 0 ? labelVolumesMm3(mesh) : std::map<Label, double>{};
    if (st.badBefore > 0) {
        TetMeshEditor editor(mesh);
        Improver imp{editor, degToScore(options.targetMinDihedralDeg), options.interfaceInsertions};
        const auto climb = [&](std::int32_t t) { return improve(imp, t, st); };
        std::vector<std::int32_t> bad = badTets(imp);
        PhaseProgress climbing(stage, progress, 0.0, 0.4);
        for (int pass = 0; pass < options.maxPasses && !bad.empty(); ++pass) {
            ++st.passes;
            const bool changed = climbing.pass(bad, climb);
            bad = badTets(imp);
            if (!changed) break;
        }
        // Iterative deepening: depth 2 only where depth 1 is stuck.
        const auto deepen = [&](int fromDepth, int toDepth, PhaseProgress& phase) {
            for (int depth = fromDepth, pass = 0; depth <= toDepth && pass < options.maxPasses && !bad.empty(); ++pass) {
                ++st.passes;
                const bool changed = phase.pass(bad, [&](std::int32_t t) { return improveWithLookahead(imp, t, depth, st); });
                bad = badTets(imp);
                if (!changed) ++depth;
            }
        };
        PhaseProgress lookahead(stage, progress, 0.4, 0.8);
        imp.trialLimit = options.lookaheadTrials;
        deepen(1, options.lookaheadDepth, lookahead);
        st.lookaheadBudgetSpent = imp.trialsMade >= imp.trialLimit;
        // The last resort, then the usual operations again around what it moved.
        InterfacePushes pushes;
        const auto push = [&](double maxMm, const std::vector<Tri>* outerFaces, PhaseProgress& pushing) {
            Acceptance accept = Acceptance::improving(imp.target);
            bool changed = pushing.pass(bad, [&](std::int32_t t) {
                return pushInterfaceNode(editor, t, maxMm, accept, pushes, st, outerFaces);
            });
            for (int pass = 0; changed && pass < options.maxPasses; ++pass) {
                ++st.passes;
                changed = pushing.pass(badTets(imp), climb);
            }
            bad = badTets(imp);
        };
        if (options.interfacePushMm > 0 && !bad.empty()) {
            PhaseProgress pushing(stage, progress, 0.8, 0.9);
            push(options.interfacePushMm, nullptr, pushing);
        }
        // The deep lookahead for the last few, within its count of trials. Straight at its depth:
        // the levels between cost more trials than they mend (SliverOptions::deepLookaheadDepth).
        PhaseProgress deeper(stage, progress, 0.9, 0.95);
        if (options.lookaheadDepth > 0 && options.deepLookaheadDepth > options.lookaheadDepth &&
            bad.size() <= options.deepLookaheadTets) {
            imp.trialLimit = imp.trialsMade + options.deepLookaheadTrials;
            deepen(options.deepLookaheadDepth, options.deepLookaheadDepth, deeper);
        }
        if (options.outerPushMm > 0 && !bad.empty()) {
            PhaseProgress outerPushing(stage, progress, 0.95, 1.0);
            const std::vector<Tri> outer = outerBoundaryFaces(editor);
            push(options.outerPushMm, &outer, outerPushing);
        }
        st.lookaheadTrials = imp.trialsMade;
        editor.finish();
        // Every operation re-triangulates a cavity of one region (or splits an interface in
        // place; pushes move it by what they recorded): a region whose volume changed otherwise
        // means a bug, and a mesh not to hand on.
        for (const auto& [label, volume] : labelVolumesMm3(mesh))
            if (std::abs(volume - volumesBefore.at(label) - pushes.volumeChange[label]) > 1e-9 * volumesBefore.at(label))
                throw Error("improveSlivers", "internal error: the volume of label " + std::to_string(label) + " changed from " +
                                                  std::to_string(volumesBefore.at(label)) + " to " + std::to_string(volume) + " mm^3");
    }
    std::tie(st.minDihedralAfterDeg, st.badAfter) = worstAndBad(mesh, options.targetMinDihedralDeg);
    st.seconds = secondsSince(start);
    if (stats) *stats = st;
    stage.update(1.0);
}

nlohmann::json toJson(const SliverStats& sl) {
    return {{"below_target_before", sl.badBefore},
            {"below_target_after", sl.badAfter},
            {"min_dihedral_before_deg", sl.minDihedralBeforeDeg},
            {"min_dihedral_after_deg", sl.minDihedralAfterDeg},
            {"smoothed", sl.smoothed},
            {"flips23", sl.flips23},
            {"flips32", sl.flips32},
            {"splits", sl.splits},
            {"face_splits", sl.faceSplits},
            {"cavity_stars", sl.cavityStars},
            {"interface_insertions", sl.interfaceInsertions},
            {"edge_removals", sl.edgeRemovals},
            {"lookaheads", sl.lookaheads},
            {"lookahead_trials", sl.lookaheadTrials},
            {"lookahead_budget_spent", sl.lookaheadBudgetSpent},
            {"interface_pushes", sl.interfacePushes},
            {"outer_pushes", sl.outerPushes},
            {"largest_push_mm", sl.largestPushMm},
            {"passes", sl.passes},
            {"seconds", sl.seconds}};
}

}  // namespace jawmesh
