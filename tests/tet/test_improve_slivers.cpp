// Sliver improvement: a grid mesh of two regions whose inner nodes were pushed around until many
// tets are flat gets its bad tets repaired without touching the interface, the boundary or the
// volume of either region.
#include "GridTetMesh.h"
#include "TetTestComplexes.h"
#include "filters/SelfIntersections.h"
#include "tet/ElementQuality.h"
#include "tet/ImproveSlivers.h"
#include "tet/TetFaceAdjacency.h"
#include "tet/TetMeshEditor.h"
#include "tet/Tetrahedralize.h"
#include "tet/ValidateTetMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace jawmesh {
namespace {

constexpr Label kBone = kMandibleBoneLabel;
const Label kTooth = toothLabel(24);

double volume(const TetMesh& m, std::size_t t) {
    const auto& e = m.tets[t];
    return signedTetVolume(m.nodes[std::size_t(e[0])], m.nodes[std::size_t(e[1])], m.nodes[std::size_t(e[2])], m.nodes[std::size_t(e[3])]);
}

/// Faces between different labels or on the outside, as sorted node triples.
std::set<std::array<std::int32_t, 3>> interfaceFaces(const TetMesh& m) {
    std::set<std::array<std::int32_t, 3>> out;
    const TetFaceAdjacency adj = tetFaceAdjacency(m);
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        const auto& f0 = adj.faces[std::size_t(adj.groupStart[g])];
        if (insideOneRegion(adj, m, g)) continue;
        out.insert(f0.key);
    }
    return out;
}

/// Area of the faces between different labels or on the outside (label 0), per sorted label
/// pair: the interface geometry, whichever way its triangles are split.
std::map<std::pair<Label, Label>, double> interfaceAreas(const TetMesh& m) {
    std::map<std::pair<Label, Label>, double> out;
    const TetFaceAdjacency adj = tetFaceAdjacency(m);
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        if (insideOneRegion(adj, m, g)) continue;
        const auto first = std::size_t(adj.groupStart[g]);
        const auto& f = adj.faces[first].key;
        Label a = m.labels[std::size_t(adj.faces[first].tet)];
        Label b = adj.groupSize(g) == 2 ? m.labels[std::size_t(adj.faces[first + 1].tet)] : kOutsideLabel;
        if (a > b) std::swap(a, b);
        const Vec3& p = m.nodes[std::size_t(f[0])];
        out[{a, b}] += 0.5 * (m.nodes[std::size_t(f[1])] - p).cross(m.nodes[std::size_t(f[2])] - p).norm();
    }
    return out;
}

void expectSameGeometry(const TetMesh& after, const TetMesh& before) {
    const auto a = interfaceAreas(after), b = interfaceAreas(before);
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [pair, area] : b) EXPECT_NEAR(a.at(pair), area, 1e-9 * area) << pair.first << "|" << pair.second;
    const auto va = labelVolumesMm3(after), vb = labelVolumesMm3(before);
    ASSERT_EQ(va.size(), vb.size());
    for (const auto& [label, vol] : vb) EXPECT_NEAR(va.at(label), vol, 1e-9 * vol) << label;
    // the nodes of the interfaces before have not moved
    for (const auto& f : interfaceFaces(before))
        for (auto v : f) EXPECT_EQ(after.nodes[std::size_t(v)], before.nodes[std::size_t(v)]);
}

/// Every node off the interface (x = 3) and off the box pushed randomly, keeping tets positive.
TetMesh distortedTwoRegionGrid() {
    TetMesh m = test::gridTetMesh(6, 6, 6, 1.0, [](const Vec3& c) { return c.x() < 3 ? kBone : kTooth; });
    std::vector<std::vector<std::size_t>> star(m.nodes.size());
    for (std::size_t t = 0; t < m.tets.size(); ++t)
        for (auto v : m.tets[t]) star[std::size_t(v)].push_back(t);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.45, 0.45);
    for (int round = 0; round < 3; ++round)
        for (std::size_t v = 0; v < m.nodes.size(); ++v) {
            const Vec3 p = m.nodes[v];
            const bool onBox = (p.array() <= 1e-9).any() || (p.array() >= 6 - 1e-9).any();
            if (onBox || std::abs(p.x() - 3) < 1e-9) continue;
            const Vec3 q = p + Vec3(u(rng), u(rng), u(rng));
            if (std::abs(q.x() - 3) < 0.05) continue;  // stay off the interface plane
            m.nodes[v] = q;
            for (auto t : star[v])
                if (volume(m, t) <= 1e-6) {
                    m.nodes[v] = p;
                    break;
                }
        }
    return m;
}

/// TetGen's own output (q2/0 under -Y, no improvement) on a tooth sphere in a PDL shell
/// `thicknessMm` thick turned against it (test::thinPdlComplex, subdivision 2).
TetMesh rawThinPdlMesh(double thicknessMm) {
    TetOptions o;
    o.radiusEdgeRatio = 2.0;
    o.repairAttempts = 0;
    o.improveSlivers = false;
    return tetrahedralize(test::thinPdlComplex(thicknessMm, 2), o);
}

TEST(ImproveSlivers, RepairsFlatTetsWithoutTouchingInterfacesOrVolumes) {
    TetMesh m = distortedTwoRegionGrid();
    const TetMesh before = m;
    const QualityStats q0 = measureQuality(m, 10.0);
    ASSERT_GT(q0.belowDihedralThreshold, 20u) << "the distortion must create slivers to repair";

    SliverStats st;
    SliverOptions noPush;
    noPush.interfacePushMm = noPush.outerPushMm = 0;  // interfaces must stay where they are (the pushes: their own test)
    improveSlivers(m, noPush, &st);
    const QualityStats q1 = measureQuality(m, 10.0);
    std::printf("below 10 deg: %zu -> %zu, min dihedral %.2f -> %.2f deg (smoothed %zu, 2-3 %zu, 3-2 %zu, splits %zu+%zu)\n",
                q0.belowDihedralThreshold, q1.belowDihedralThreshold, q0.minDihedralDeg, q1.minDihedralDeg, st.smoothed,
                st.flips23, st.flips32, st.splits, st.faceSplits);
    EXPECT_EQ(st.badBefore, q0.belowDihedralThreshold);
    EXPECT_EQ(st.badAfter, q1.belowDihedralThreshold);
    EXPECT_NEAR(st.minDihedralAfterDeg, q1.minDihedralDeg, 1e-9);
    EXPECT_LE(q1.belowDihedralThreshold, q0.belowDihedralThreshold / 10);
    EXPECT_GT(q1.minDihedralDeg, q0.minDihedralDeg + 3.0);

    EXPECT_TRUE(validateTetMesh(m, {}).valid());
    for (std::size_t t = 0; t < m.tets.size(); ++t) EXPECT_GT(volume(m, t), 0.0) << t;
    // interfaces and the outside: the same area on unmoved nodes (split by nodes on them at most)
    expectSameGeometry(m, before);
    // each region keeps its volume (3 x 6 x 6 mm^3 each)
    const auto vol = labelVolumesMm3(m);
    EXPECT_NEAR(vol.at(kBone), 108.0, 1e-9);
    EXPECT_NEAR(vol.at(kTooth), 108.0, 1e-9);

    // without interface insertions the interface faces themselves stay exactly as they were
    TetMesh kept = distortedTwoRegionGrid();
    SliverOptions inside = noPush;
    inside.interfaceInsertions = false;
    improveSlivers(kept, inside);
    EXPECT_EQ(interfaceFaces(kept), interfaceFaces(before));
}

TEST(ImproveSlivers, InterfaceInsertionsMendSliversBetweenTwoCloseInterfaces) {
    // TetGen under -Y on a PDL 0.04 mm thick between spheres of 0.3 mm edges turned against each
    // other: its tets can only span the two spheres' nodes, and many are slivers that nothing
    // inside one region can mend.
    const TetMesh raw = rawThinPdlMesh(0.04);
    const QualityStats q0 = measureQuality(raw, 10.0);
    ASSERT_GT(q0.belowDihedralThreshold, 0u) << "the thin PDL must give slivers";

    TetMesh inside = raw, across = raw;
    SliverOptions noInsertions, insertions;  // both without the lookahead, measured on its own below
    noInsertions.interfaceInsertions = false;
    noInsertions.lookaheadDepth = insertions.lookaheadDepth = 0;
    noInsertions.interfacePushMm = insertions.interfacePushMm = 0;
    noInsertions.outerPushMm = insertions.outerPushMm = 0;
    SliverStats s0, s1;
    improveSlivers(inside, noInsertions, &s0);
    improveSlivers(across, insertions, &s1);
    std::printf("below 10 deg: %zu from TetGen, %zu inside the regions only, %zu with %zu interface insertions (min %.2f deg)\n",
                q0.belowDihedralThreshold, s0.badAfter, s1.badAfter, s1.interfaceInsertions, s1.minDihedralAfterDeg);
    EXPECT_GT(s0.badAfter, 0u) << "the regions alone cannot mend these";
    EXPECT_GT(s1.interfaceInsertions, 0u);
    // measured: 389 from TetGen, 234 inside the regions only, 127 with 72 insertions
    EXPECT_LT(s1.badAfter, s0.badAfter * 3 / 4);
    EXPECT_GE(s1.minDihedralAfterDeg, s0.minDihedralAfterDeg);
    EXPECT_TRUE(validateTetMesh(across, {}).valid());
    for (std::size_t t = 0; t < across.tets.size(); ++t) ASSERT_GT(volume(across, t), 0.0) << t;
    expectSameGeometry(across, raw);
}

TEST(ImproveSlivers, LookaheadMendsWhatNoSingleOperationCanAndUndoesWhatDoesNotHelp) {
    // The thin PDL of the test above (coarser): the hill climbing stops where every single operation
    // would lower the tets it changes; trying each candidate anyway and improving around it
    // mends more, and the trials that do not help leave no trace (geometry, validity).
    const TetMesh raw = rawThinPdlMesh(0.045);
    TetMesh climbed = raw, looked = raw;
    SliverOptions noLookahead, lookahead;
    noLookahead.lookaheadDepth = 0;
    noLookahead.interfacePushMm = lookahead.interfacePushMm = 0;
    noLookahead.outerPushMm = lookahead.outerPushMm = 0;
    SliverStats s0, s1;
    improveSlivers(climbed, noLookahead, &s0);
    improveSlivers(looked, lookahead, &s1);
    std::printf("below 10 deg: %zu from TetGen, %zu hill climbing, %zu with the lookahead (%zu kept, min %.2f -> %.2f deg)\n",
                s0.badBefore, s0.badAfter, s1.badAfter, s1.lookaheads, s0.minDihedralAfterDeg, s1.minDihedralAfterDeg);
    ASSERT_GT(s0.badAfter, 0u) << "the hill climbing must leave tets for the lookahead";
    EXPECT_GT(s1.lookaheads, 0u);
    EXPECT_LT(s1.badAfter, s0.badAfter);
    EXPECT_EQ(s1.badAfter, measureQuality(looked, 10.0).belowDihedralThreshold);
    EXPECT_TRUE(validateTetMesh(looked, {}).valid());
    for (std::size_t t = 0; t < looked.tets.size(); ++t) ASSERT_GT(volume(looked, t), 0.0) << t;
    expectSameGeometry(looked, raw);
    // deterministic, undone trials included
    TetMesh again = raw;
    improveSlivers(again, lookahead);
    EXPECT_EQ(again.tets, looked.tets);
    EXPECT_EQ(again.nodes, looked.nodes);
}

/// A tooth lip `liftMm` thick on the outside: one flat tooth tet over a boundary triangle of edge
/// 0.05 mm, its apex v an interface node under three PDL tets (v is inside the mesh).
TetMesh thinLip(double liftMm) {
    const double s = 0.05;
    const Vec3 a(0, 0, 0), b(s, 0, 0), c(s / 2, s * std::sqrt(3.0) / 2, 0);
    const Vec3 g = (a + b + c) / 3.0;
    TetMesh m;
    m.nodes = {a, b, c, g + Vec3(0, 0, liftMm), g + Vec3(0, 0, s)};
    const auto add = [&](Tet e, Label l) {
        if (volume(TetMesh{m.nodes, {e}, {l}}, 0) < 0) std::swap(e[2], e[3]);
        m.tets.push_back(e);
        m.labels.push_back(l);
    };
    add({0, 1, 2, 3}, kTooth);
    add({0, 1, 3, 4}, pdlLabel(24));
    add({1, 2, 3, 4}, pdlLabel(24));
    add({2, 0, 3, 4}, pdlLabel(24));
    return m;
}

TEST(ImproveSlivers, LastResortPushesAnInterfaceNodeOffAThinLipWithinItsBound) {
    // A lip 0.002 mm thick (as the shared mandible's fine extraction has at a few crest spots):
    // its tet is 7.9 degrees whatever the triangulation, until its interface node moves.
    const TetMesh lip = thinLip(0.002);
    ASSERT_LT(measureQuality(lip, 10.0).minDihedralDeg, 10.0);
    TetMesh kept = lip, pushed = lip;
    SliverOptions off;
    off.interfacePushMm = off.outerPushMm = 0;
    SliverStats s0, s1;
    improveSlivers(kept, off, &s0);
    improveSlivers(pushed, SliverOptions{}, &s1);
    std::printf("lip: %zu under 10 deg without pushes (min %.2f deg); %zu with %zu push of %.4f mm (min %.2f deg)\n", s0.badAfter,
                s0.minDihedralAfterDeg, s1.badAfter, s1.interfacePushes, s1.largestPushMm, s1.minDihedralAfterDeg);
    EXPECT_GT(s0.badAfter, 0u) << "nothing but a push mends the lip";
    EXPECT_EQ(s1.badAfter, 0u);
    EXPECT_EQ(s1.interfacePushes, 1u);
    EXPECT_LE(s1.largestPushMm, SliverOptions{}.interfacePushMm);
    // only v moved, straight up (away from the boundary triangle), by the reported push
    ASSERT_GE(pushed.nodes.size(), lip.nodes.size());
    for (std::size_t v = 0; v < lip.nodes.size(); ++v) {
        if (v == 3) continue;
        EXPECT_EQ(pushed.nodes[v], lip.nodes[v]) << "node " << v;
    }
    const Vec3 move = pushed.nodes[3] - lip.nodes[3];
    EXPECT_NEAR(move.head<2>().norm(), 0.0, 1e-12);
    EXPECT_NEAR(move.z(), s1.largestPushMm, 1e-12);
    EXPECT_TRUE(validateTetMesh(pushed, {}).valid());
    for (std::size_t t = 0; t < pushed.tets.size(); ++t) EXPECT_GT(volume(pushed, t), 0.0) << t;
    // the mesh's outer surface is where it was: the whole volume is unchanged
    double total0 = 0, total1 = 0;
    for (const auto& [label, v] : labelVolumesMm3(lip)) total0 += v;
    for (const auto& [label, v] : labelVolumesMm3(pushed)) total1 += v;
    EXPECT_NEAR(total1, total0, 1e-15);
}

TEST(ImproveSlivers, LeavesAGoodMeshAloneAndIsDeterministic) {
    TetMesh good = test::gridTetMesh(3, 3, 3, 1.0, [](const Vec3&) { return kBone; });
    const TetMesh copy = good;
    SliverStats st;
    improveSlivers(good, SliverOptions{}, &st);
    EXPECT_EQ(st.badBefore, 0u);
    EXPECT_EQ(good.tets, copy.tets);
    EXPECT_EQ(good.nodes, copy.nodes);

    TetMesh a = distortedTwoRegionGrid(), b = distortedTwoRegionGrid();
    improveSlivers(a);
    improveSlivers(b);
    EXPECT_EQ(a.tets, b.tets);
    EXPECT_EQ(a.nodes, b.nodes);
}

/// Records the stages and fractions it is given; cancels after `cancelAfter` polls (never: -1).
class RecordingProgress : public Progress {
public:
    explicit RecordingProgress(int cancelAfter = -1) : cancelAfter_(cancelAfter) {}
    void begin(const std::string& stage) override { stages.push_back(stage); }
    void update(double fraction) override { fractions.push_back(fraction); }
    bool cancelled() const override { return cancelAfter_ >= 0 && polls_++ >= cancelAfter_; }
    std::vector<std::string> stages;
    std::vector<double> fractions;

private:
    int cancelAfter_;
    mutable int polls_ = 0;
};

TEST(ImproveSlivers, ReportsProgressWithoutChangingTheResultAndStopsWhenCancelled) {
    TetMesh quiet = distortedTwoRegionGrid(), reported = distortedTwoRegionGrid();
    improveSlivers(quiet);
    RecordingProgress progress;
    improveSlivers(reported, SliverOptions{}, nullptr, progress);
    EXPECT_EQ(reported.tets, quiet.tets);
    EXPECT_EQ(reported.nodes, quiet.nodes);
    ASSERT_EQ(progress.stages, std::vector<std::string>{"improve slivers"});
    ASSERT_FALSE(progress.fractions.empty());
    EXPECT_TRUE(std::is_sorted(progress.fractions.begin(), progress.fractions.end()));
    EXPECT_GE(progress.fractions.front(), 0.0);
    EXPECT_EQ(progress.fractions.back(), 1.0);

    TetMesh stopped = distortedTwoRegionGrid();
    RecordingProgress cancel(3);
    EXPECT_THROW(improveSlivers(stopped, SliverOptions{}, nullptr, cancel), Cancelled);
}

}  // namespace
}  // namespace jawmesh

/// One flat tooth tet on the outside, `liftMm` high over a boundary triangle of edge 0.05 mm (every
/// node on the outer boundary), and, when `roofGapMm` > 0, a second tooth tet whose bottom face
/// lies that far above the flat tet's apex (a surface across a narrow gap of outside).
TetMesh outerLip(double liftMm, double roofGapMm) {
    const double s = 0.05;
    const Vec3 a(0, 0, 0), b(s, 0, 0), c(s / 2, s * std::sqrt(3.0) / 2, 0);
    const Vec3 g = (a + b + c) / 3.0;
    TetMesh m;
    m.nodes = {a, b, c, g + Vec3(0, 0, liftMm)};
    m.tets = {{0, 1, 2, 3}};
    m.labels = {kTooth};
    if (roofGapMm > 0) {
        const double z = liftMm + roofGapMm;
        for (const Vec3& p : {Vec3(-s, -s, z), Vec3(2 * s, -s, z), Vec3(s / 2, 2 * s, z), Vec3(s / 2, 0, z + s)}) m.nodes.push_back(p);
        m.tets.push_back({4, 5, 6, 7});
        m.labels.push_back(kTooth);
    }
    for (auto& e : m.tets)
        if (volume(TetMesh{m.nodes, {e}, {kTooth}}, 0) < 0) std::swap(e[2], e[3]);
    return m;
}

/// The outer boundary's faces of a mesh (faces of one tet only) as a surface, for the exact
/// self-intersection check.
SurfaceMesh outerSurface(const TetMesh& m) {
    SurfaceMesh s;
    s.vertices = m.nodes;
    const TetFaceAdjacency adj = tetFaceAdjacency(m);
    for (std::size_t g = 0; g < adj.groupCount(); ++g)
        if (adj.groupSize(g) == 1) s.triangles.push_back(adj.faces[std::size_t(adj.groupStart[g])].key);
    return s;
}

TEST(ImproveSlivers, LastResortPushesAnOuterNodeOnlyWhereTheOuterSurfaceStaysFree) {
    // A crown lip 0.002 mm thick against the outside: its one tet is 7.9 degrees, and every node is
    // on the outer boundary, so only the outer push mends it.
    const TetMesh lip = outerLip(0.002, 0);
    ASSERT_LT(measureQuality(lip, 10.0).minDihedralDeg, 10.0);
    TetMesh kept = lip, pushed = lip;
    SliverOptions off;
    off.outerPushMm = 0;
    SliverStats s0, s1;
    improveSlivers(kept, off, &s0);
    improveSlivers(pushed, SliverOptions{}, &s1);
    std::printf("outer lip: %zu under 10 deg without outer pushes (%zu lookahead trials, %.2f s); %zu with %zu push of %.4f mm (%.2f s)\n",
                s0.badAfter, s0.lookaheadTrials, s0.seconds, s1.badAfter, s1.outerPushes, s1.largestPushMm, s1.seconds);
    EXPECT_GT(s0.badAfter, 0u) << "nothing but an outer push mends the lip";
    EXPECT_EQ(s1.badAfter, 0u);
    EXPECT_EQ(s1.outerPushes, 1u);
    EXPECT_LE(s1.largestPushMm, SliverOptions{}.outerPushMm);
    EXPECT_NEAR((pushed.nodes[3] - lip.nodes[3]).z(), s1.largestPushMm, 1e-12);
    EXPECT_TRUE(validateTetMesh(pushed, {}).valid());

    // The same lip under another tooth's face 0.001 mm above its apex: the push may not carry the
    // apex through that face (the outer surface would intersect itself).
    TetMesh roofed = outerLip(0.002, 0.001);
    SliverStats s2;
    improveSlivers(roofed, SliverOptions{}, &s2);
    std::printf("roofed lip: %zu under 10 deg, %zu outer pushes, %zu lookahead trials, %.2f s\n", s2.badAfter, s2.outerPushes,
                s2.lookaheadTrials, s2.seconds);
    EXPECT_TRUE(findSelfIntersections(outerSurface(roofed)).pairs.empty());
    EXPECT_LT(roofed.nodes[3].z(), 0.003);
    EXPECT_TRUE(validateTetMesh(roofed, {}).valid());
}

// The improver rescores only what the editor reports touched between its passes: every tet whose
// score may differ (moved, moved back by a rollback, re-added under a new index) must be reported.
TEST(TetMeshEditor, ReportsEveryTetWhoseScoreMayHaveChanged) {
    TetMesh m = test::gridTetMesh(3, 3, 3, 1.0, [](const Vec3&) { return Label(1); });
    TetMeshEditor editor(m);
    std::vector<double> before(editor.tetCount());
    for (std::size_t t = 0; t < before.size(); ++t) before[t] = editor.score(std::int32_t(t));
    EXPECT_TRUE(editor.takeTouched().empty());
    const std::int32_t v = 21;  // node (1, 1, 1): inside, free to move
    ASSERT_FALSE(editor.fixed(v));
    editor.checkpoint();
    editor.move(v, editor.node(v) + Vec3(0.1, 0.05, 0.0));
    editor.rollback();  // back where it was
    const std::vector<std::int32_t> afterRollback = editor.takeTouched();
    for (std::int32_t t : editor.star(v))
        EXPECT_NE(std::find(afterRollback.begin(), afterRollback.end(), t), afterRollback.end());
    editor.move(v, editor.node(v) + Vec3(-0.1, 0.1, 0.05));
    const std::int32_t t0 = editor.star(v).front();
    editor.replace({t0}, {editor.tet(t0)}, editor.label(t0));  // the same tet under a new index
    std::vector<std::int32_t> touched = editor.takeTouched();
    std::sort(touched.begin(), touched.end());
    std::size_t changed = 0;
    for (std::size_t t = 0; t < editor.tetCount(); ++t) {
        if (!editor.alive(std::int32_t(t))) continue;
        if (t < before.size() && editor.score(std::int32_t(t)) == before[t]) continue;
        ++changed;
        EXPECT_TRUE(std::binary_search(touched.begin(), touched.end(), std::int32_t(t))) << "tet " << t;
    }
    EXPECT_GE(changed, editor.star(v).size());  // the moved node's whole star, the re-added tet in it
    EXPECT_TRUE(editor.takeTouched().empty());
}
