// The tet stage's driver: the checks of the complex and the options, then the attempt ladder
// (kLadder: TetGen runs with stronger settings while tets under the target are left, each labeled
// and improved, the best kept), with the refinement rounds before its last rung (the one that makes
// far more tets). TetGen itself is tet/TetgenAdapter.cpp.
#include "tet/Tetrahedralize.h"

#include "filters/OpenRegionEdges.h"
#include "filters/SelfIntersections.h"
#include "io/Error.h"
#include "io/ResourceUsage.h"
#include "tet/ElementQuality.h"
#include "tet/LabelFromSides.h"
#include "tet/RefineComplex.h"
#include "tet/RepairHoles.h"
#include "tet/TetgenAdapter.h"
#include "tet/TetgenGroups.h"
#include "tet/TetStageName.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

namespace jawmesh {
namespace {

std::string pointText(const Vec3& p) { return "(" + tetgenNumber(p.x()) + ", " + tetgenNumber(p.y()) + ", " + tetgenNumber(p.z()) + ")"; }

// ---- checks of the input ----

/// TetGen meshes a complex with a hole as readily as a closed one, and its tets then join the
/// regions on both sides of the hole: found only after the whole run, as an open region boundary
/// of the labelling. Checked first (after repairHoles), so the message names the hole.
void rejectOpenRegions(const InterfaceComplex& plc, const HoleFillStats& repair) {
    const std::vector<OpenRegionEdge> open = openRegionEdges(plc);
    if (open.empty()) return;
    std::size_t edges = 0;
    for (std::size_t i = 0; i < open.size(); ++i) edges += i == 0 || open[i].a != open[i - 1].a || open[i].b != open[i - 1].b;
    // name a region rather than the outside (every hole is in both)
    const auto first = std::find_if(open.begin(), open.end(), [](const OpenRegionEdge& e) { return e.label != kOutsideLabel; });
    const OpenRegionEdge& e = first != open.end() ? *first : open[0];
    const Vec3 p = 0.5 * (plc.surface.vertices[std::size_t(e.a)] + plc.surface.vertices[std::size_t(e.b)]);
    throw Error(kTetStageName, "the interface surface has holes: " + std::to_string(edges) +
                           " edges where a region's boundary stops (the first on the boundary of " + labelName(e.label) +
                           " near " + pointText(p) + "; " + std::to_string(repair.filled.size()) + " holes closed, " +
                           std::to_string(repair.left.size()) + " could not be); the regions would mesh into each other");
}

void checkComplex(const InterfaceComplex& plc) {
    const auto& s = plc.surface;
    if (s.triangles.empty()) throw Error(kTetStageName, "the interface complex has no triangles");
    if (plc.sides.size() != s.triangles.size())
        throw Error(kTetStageName, "the interface complex has " + std::to_string(plc.sides.size()) + " side pairs for " +
                               std::to_string(s.triangles.size()) + " triangles");
    if (!plc.carried.empty())  // points on no facet, some exactly on one: TetGen may crash on them
        throw Error(kTetStageName, "the interface complex still carries the adaptive extraction's vertices (simplify it, or withoutCarried)");
    if (plc.seeds.empty()) throw Error(kTetStageName, "the interface complex has no region seeds");
    const auto nv = static_cast<std::int64_t>(s.vertices.size());
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        for (auto v : s.triangles[t])
            if (v < 0 || v >= nv) throw Error(kTetStageName, "triangle " + std::to_string(t) + " has a vertex index out of range");
        if (plc.sides[t][0] == plc.sides[t][1])
            throw Error(kTetStageName, "triangle " + std::to_string(t) + " separates label " + std::to_string(plc.sides[t][0]) +
                                   " from itself");
    }
    for (const auto& seed : plc.seeds) {
        if (seed.label == kOutsideLabel) throw Error(kTetStageName, "a region seed has the outside label 0");
        if (!seed.point.allFinite()) throw Error(kTetStageName, "a region seed is not finite");
        labelKind(seed.label);  // throws for unknown labels
    }
}

void checkOptions(const TetOptions& o) {
    if (!(o.radiusEdgeRatio > 1.0)) throw Error(kTetStageName, "the radius-edge bound must be > 1 (TetGen -q)");
    if (o.slivers.targetMinDihedralDeg < 0 || o.slivers.targetMinDihedralDeg >= 70)
        throw Error(kTetStageName, "the minimum dihedral angle must be in [0, 70) degrees");
    if (o.tetgenMinDihedralDeg >= 70) throw Error(kTetStageName, "TetGen's minimum dihedral angle must be below 70 degrees");
}

/// TetGen 1.5.0 crashes (double free while unwinding from terminatetetgen) instead of throwing
/// when it meets intersecting facets during meshing, so the surface is checked exactly first
/// (filters/SelfIntersections.h: parallel, touching counts). TetGen's own diagnosis (-d) took
/// about 19 s on the shared mandible's 245 k triangles; this takes well under a second.
void rejectSelfIntersections(const InterfaceComplex& plc) {
    const SelfIntersectionReport report = findSelfIntersections(plc.surface);
    if (report.clean()) return;
    const std::int32_t first = report.pairs.empty() ? report.degenerate.front() : report.pairs.front().first;
    Vec3 c = Vec3::Zero();
    for (std::int32_t v : plc.surface.triangles[std::size_t(first)]) c += plc.surface.vertices[std::size_t(v)] / 3.0;
    throw Error(kTetStageName, "the interface surface intersects itself (" + std::to_string(report.pairs.size()) +
                           " intersecting triangle pairs, " + std::to_string(report.degenerate.size()) +
                           " degenerate triangles; the first near " + pointText(c) + ")");
}

// ---- the attempt ladder ----


/// One rung of the ladder: how its TetGen run differs from the options.
struct Rung {
    int minOptimizationLevel;          ///< -O level: the options' one, but at least this
    double maxRadiusEdge;              ///< -q radius-edge bound: the options' one, but at most this
    double optMaxDihedralDeg;          ///< target of TetGen's optimisation for the largest dihedral
    bool targetAsTetgenDihedral;       ///< -q/<deg> is the target even when tetgenMinDihedralDeg is set
    bool keptOnlyWhenItMeetsTheBound;  ///< not merely when better: only when it leaves no tet under the target
};

constexpr double kAnyRatio = std::numeric_limits<double>::infinity();

/// The TetGen runs tried in turn while tets under the target are left: the first, then up to
/// TetOptions::repairAttempts more.
constexpr Rung kLadder[] = {
    // The options as given.
    {0, kAnyRatio, kTetgenDefaultOptMaxDihedralDeg, false, false},
    // Stronger optimisation: more passes, then a lower target for the largest dihedral (which
    // removes slivers, whose small angles come with angles near 180).
    {7, kAnyRatio, 155.0, false, false},
    // Last, at most radius-edge 1.5 with TetGen's own dihedral bound: more tets (the mandible
    // 1.30 M instead of 0.99 M at 2/0), kept only when it leaves no tet under the bound where the
    // others did (the one-tooth phantom: 0 instead of 2). Tighter still (1.3, tried before) gave
    // 1.76 M tets and no fewer under 10 degrees.
    {9, 1.5, 150.0, true, true},
};
constexpr std::size_t kLadderRungs = sizeof kLadder / sizeof kLadder[0];

std::string tetgenSwitches(const TetOptions& o, const Rung& rung) {
    const double dihedral = o.tetgenMinDihedralDeg >= 0 && !rung.targetAsTetgenDihedral ? o.tetgenMinDihedralDeg
                                                                                          : o.slivers.targetMinDihedralDeg;
    std::string sw = "pzQA";
    sw += "q" + tetgenNumber(std::min(o.radiusEdgeRatio, rung.maxRadiusEdge)) + "/" + tetgenNumber(dihedral);
    const bool regional = o.boneEdgeMm > 0 || o.toothEdgeMm > 0 || o.pdlEdgeMm > 0;
    if (regional) sw += "a";
    if (o.maxEdgeMm > 0) sw += "a" + tetgenNumber(tetVolumeForEdge(o.maxEdgeMm));
    if (o.preserveBoundary) sw += "Y";
    if (!o.mergeCoplanarFacets) sw += "M";
    sw += "O" + std::to_string(std::clamp(std::max(o.optimizationLevel, rung.minOptimizationLevel), 0, 9)) + "/7";
    return sw;
}

/// The switches and their optimisation target as run.json names them.
std::string switchesText(const TetgenRun& run) {
    if (run.optMaxDihedralDeg == kTetgenDefaultOptMaxDihedralDeg) return run.switches;
    return run.switches + " (optmaxdihedral " + tetgenNumber(run.optMaxDihedralDeg) + ")";
}

/// The ladder's state: the best mesh so far and what made it, and what every run needs.
struct Ladder {
    const TetOptions& options;
    Progress& progress;
    TetStats& stats;
    TetMesh best{};
    QualityStats bestQuality{};
    bool haveBest = false;
    std::size_t bestRung = 0;

    bool metTheTarget() const { return haveBest && bestQuality.belowDihedralThreshold == 0; }
};

bool isBetter(const Ladder& l, const QualityStats& q, bool onlyWhenItMeetsTheTarget) {
    if (!l.haveBest) return true;
    const QualityStats& b = l.bestQuality;
    if (onlyWhenItMeetsTheTarget) return q.belowDihedralThreshold == 0 && b.belowDihedralThreshold > 0;
    return q.belowDihedralThreshold < b.belowDihedralThreshold ||
           (q.belowDihedralThreshold == b.belowDihedralThreshold && q.minDihedralDeg > b.minDihedralDeg);
}

/// One TetGen run of rung `r` on `complex` (in a child process when isolated), labeled, its
/// slivers improved; kept when better than the best so far (true). Throws what TetGen or the
/// labelling throws.
bool attempt(Ladder& l, const InterfaceComplex& complex, std::size_t r, bool onlyWhenItMeetsTheTarget, bool isolated) {
    const TetOptions& o = l.options;
    ++l.stats.attempts;
    const TetgenRun run{tetgenSwitches(o, kLadder[r]), kLadder[r].optMaxDihedralDeg, seedVolumeBounds(complex, o)};
    TetgenMesh raw = runTetgenInGroups(complex, run, o.preserveBoundary, isolated, l.stats.childPeakMemoryBytes);
    const std::size_t removed = keepLabeled(raw.mesh);
    if (raw.mesh.tets.empty()) throw Error(kTetStageName, "no tetrahedron received a label: are the seeds inside their regions?");
    SliverStats slivers;
    if (o.improveSlivers) improveSlivers(raw.mesh, o.slivers, &slivers, l.progress);
    const QualityStats q = measureQuality(raw.mesh, o.slivers.targetMinDihedralDeg);
    if (!isBetter(l, q, onlyWhenItMeetsTheTarget)) return false;
    l.best = std::move(raw.mesh);
    l.bestQuality = q;
    l.haveBest = true;
    l.bestRung = r;
    l.stats.switches = switchesText(run);
    l.stats.outsideTetsRemoved = removed;
    l.stats.slivers = slivers;
    return true;
}

/// The rungs [first, last) in turn, until one leaves no tet under the target. A failing rung after
/// the first only adds to stats.failedAttempts.
void climbLadder(Ladder& l, const InterfaceComplex& plc, std::size_t first, std::size_t last, ProgressStage& stage, double stageSteps) {
    for (std::size_t r = first; r < last && !l.metTheTarget(); ++r) {
        l.progress.checkCancelled();
        stage.update(static_cast<double>(l.stats.attempts) / stageSteps);  // TetGen runs made so far
        try {
            attempt(l, plc, r, kLadder[r].keptOnlyWhenItMeetsTheBound, false);
        } catch (const Error& e) {
            // A repair run exists only to improve angles: when it fails (TetGen's stronger
            // optimisation has lost a facet on a valid surface), the mesh already made stands.
            if (!l.haveBest) throw;
            l.stats.failedAttempts.push_back(tetgenSwitches(l.options, kLadder[r]) + ": " + e.what());
        }
    }
}

/// Refinement rounds (tet/RefineComplex.h): the surface edges around the tets still under the
/// target are split and the kept rung runs again (in a child process: TetGen has aborted on such
/// surfaces), while that leaves fewer such tets.
void refineRounds(Ladder& l, const InterfaceComplex& plc, ProgressStage& stage, double stageSteps) {
    const double target = l.options.slivers.targetMinDihedralDeg;
    InterfaceComplex refined;  // the complex of the last kept round
    for (int round = 0; round < l.options.refineRounds && l.bestQuality.belowDihedralThreshold > 0; ++round) {
        l.progress.checkCancelled();
        stage.update(static_cast<double>(l.stats.attempts) / stageSteps);
        InterfaceComplex next = round == 0 ? plc : refined;
        const std::size_t split = splitComplexEdges(next, edgesAroundBadTets(next, l.best, target));
        if (split == 0) break;
        try {
            if (!attempt(l, next, l.bestRung, false, true)) break;
        } catch (const Error& e) {
            l.stats.failedAttempts.push_back("refinement round " + std::to_string(round + 1) + ": " + e.what());
            break;
        }
        refined = std::move(next);
        l.stats.refinedEdges += split;
        ++l.stats.refineRounds;
    }
}

/// The last resort after the ladder (TetOptions::finalInterfacePushMm): the kept mesh improved
/// once more with longer interface pushes, kept when better.
void finalPush(Ladder& l) {
    const TetOptions& o = l.options;
    // A caller that allows no interface pushes wants the surface where it is.
    if (!o.improveSlivers || o.finalInterfacePushMm <= 0 || o.slivers.interfacePushMm <= 0 || !l.haveBest || l.metTheTarget()) return;
    l.progress.checkCancelled();
    TetMesh mesh = l.best;
    SliverOptions longer = o.slivers;
    longer.interfacePushMm = o.finalInterfacePushMm;
    l.stats.finalPush.emplace();
    try {
        improveSlivers(mesh, longer, &*l.stats.finalPush, l.progress);
    } catch (const Error& e) {
        // It exists only to improve angles: the mesh already made stands.
        l.stats.failedAttempts.push_back("final push: " + std::string(e.what()));
        return;
    }
    const QualityStats q = measureQuality(mesh, o.slivers.targetMinDihedralDeg);
    if (!isBetter(l, q, false)) return;
    l.best = std::move(mesh);
    l.bestQuality = q;
    l.stats.finalPushKept = true;
}

}  // namespace

double tetVolumeForEdge(double edgeMm) { return edgeMm * edgeMm * edgeMm / (6.0 * std::sqrt(2.0)); }

std::vector<double> seedVolumeBounds(const InterfaceComplex& plc, const TetOptions& o) {
    std::vector<double> bounds;
    for (const RegionSeed& seed : plc.seeds) {
        double edge = 0;
        switch (labelKind(seed.label)) {
        case LabelKind::Bone: edge = o.boneEdgeMm; break;
        case LabelKind::Tooth:
        case LabelKind::Implant: edge = o.toothEdgeMm; break;
        case LabelKind::Pdl: edge = o.pdlEdgeMm; break;
        default: break;
        }
        bounds.push_back(edge > 0 ? tetVolumeForEdge(edge) : -1.0);
    }
    return bounds;
}

std::string firstTetgenSwitches(const TetOptions& options) { return tetgenSwitches(options, kLadder[0]); }

TetMesh tetrahedralize(const InterfaceComplex& input, const TetOptions& options, Progress& progress, TetStats* stats) {
    ProgressStage stage(progress, kTetStageName);
    checkComplex(input);
    TetStats st;
    InterfaceComplex repaired;
    const InterfaceComplex& plc = repairHoles(input, repaired, seedVolumeBounds(input, options), st);
    rejectOpenRegions(plc, st.holeRepair);
    checkOptions(options);
    if (options.checkIntersections || &plc != &input) rejectSelfIntersections(plc);  // a repaired surface always

    st.inputVertices = input.surface.vertices.size();
    st.inputTriangles = input.surface.triangles.size();
    const std::size_t runs = std::min(kLadderRungs, static_cast<std::size_t>(1 + std::max(0, options.repairAttempts)));
    const double stageSteps = static_cast<double>(runs + std::size_t(std::max(0, options.refineRounds)));  // TetGen runs at most
    const auto start = std::chrono::steady_clock::now();
    Ladder ladder{options, progress, st};
    // The last rung (radius-edge 1.5) makes far more tets than the refinement rounds' few split
    // edges, so it comes after them: the shared maxilla met the bound with 564 k tets by a round
    // and with 860 k by that rung once the outer pushes let it (docs/BENCHMARKS.md, session 28).
    const std::size_t cheapRungs = std::min(runs, kLadderRungs - 1);
    climbLadder(ladder, plc, 0, cheapRungs, stage, stageSteps);
    refineRounds(ladder, plc, stage, stageSteps);
    climbLadder(ladder, plc, cheapRungs, runs, stage, stageSteps);
    finalPush(ladder);
    st.seconds = secondsSince(start);
    st.nodes = ladder.best.nodes.size();
    st.tets = ladder.best.tets.size();
    st.minDihedralDeg = ladder.bestQuality.minDihedralDeg;
    st.maxRadiusEdge = ladder.bestQuality.maxRadiusEdge;
    st.belowMinDihedral = ladder.bestQuality.belowDihedralThreshold;
    if (stats) *stats = st;
    stage.update(1.0);
    return std::move(ladder.best);
}

nlohmann::json toJson(const TetStats& stats) {
    return {{"hole_repair", toJson(stats.holeRepair)},
            {"switches", stats.switches},
            {"attempts", stats.attempts},
            {"failed_attempts", stats.failedAttempts},
            {"refine_rounds", stats.refineRounds},
            {"refined_edges", stats.refinedEdges},
            {"child_peak_memory_bytes", stats.childPeakMemoryBytes},
            {"seconds", stats.seconds},
            {"sliver_improvement", toJson(stats.slivers)},
            {"final_push", stats.finalPush ? nlohmann::json{{"kept", stats.finalPushKept}, {"improvement", toJson(*stats.finalPush)}}
                                           : nlohmann::json(nullptr)}};
}

}  // namespace jawmesh
