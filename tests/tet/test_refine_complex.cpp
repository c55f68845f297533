// Local refinement of an interface complex (tet/RefineComplex.h): splitting surface edges keeps the
// surface (region volumes, sides, closure) and the refinement rounds of tetrahedralize() use it.
#include "io/SurfaceMesh.h"
#include "tet/ElementQuality.h"
#include "tet/RefineComplex.h"
#include "tet/Tetrahedralize.h"
#include "tet/ValidateTetMesh.h"
#include "TetTestComplexes.h"

#include <gtest/gtest.h>

#include <map>

using namespace jawmesh;

namespace {

/// Triangles on each undirected edge.
std::map<std::uint64_t, int> edgeUse(const SurfaceMesh& s) {
    std::map<std::uint64_t, int> use;
    for (const Tri& t : s.triangles)
        for (int i = 0; i < 3; ++i) use[edgeKey(t[std::size_t(i)], t[std::size_t((i + 1) % 3)])]++;
    return use;
}

}  // namespace

TEST(RefineComplex, SplitEdgesKeepVolumesSidesAndClosure) {
    // The voxel jaw block: bone, two teeth, their PDLs; its crest edges are junctions of three
    // interfaces (tooth/PDL/outside), split like any other.
    InterfaceComplex c = test::complexFromVoxels(test::jawBlockScene());
    const auto volumesBefore = test::complexVolumes(c);
    const auto useBefore = edgeUse(c.surface);
    std::vector<std::array<std::int32_t, 2>> edges;
    std::size_t incidences = 0, junctions = 0;
    for (const auto& [key, n] : useBefore)
        if (edges.size() < 400 && key % 7 == 0) {  // a spread of edges
            edges.push_back({std::int32_t(key >> 32), std::int32_t(key & 0xffffffffu)});
            incidences += std::size_t(n);
            junctions += n > 2;
        }
    ASSERT_GT(junctions, 0u) << "the edges split must include junctions of three interfaces";
    edges.push_back({0, 0});  // not an edge: skipped
    const std::size_t vertices = c.surface.vertices.size(), triangles = c.surface.triangles.size();
    EXPECT_EQ(splitComplexEdges(c, edges), edges.size() - 1);
    EXPECT_EQ(c.surface.vertices.size(), vertices + edges.size() - 1);
    EXPECT_EQ(c.surface.triangles.size(), triangles + incidences);
    ASSERT_EQ(c.sides.size(), c.surface.triangles.size());
    // Same regions, same volumes: every child kept its parent's sides and orientation.
    const auto volumesAfter = test::complexVolumes(c);
    ASSERT_EQ(volumesAfter.size(), volumesBefore.size());
    for (const auto& [label, v] : volumesBefore) EXPECT_NEAR(volumesAfter.at(label), v, 1e-9 * v) << label;
    // No crack: every edge still has at least two triangles (a triangle left unsplit on a split
    // edge would leave its halves with one each), and the split edges are gone.
    for (const auto& [key, n] : edgeUse(c.surface)) EXPECT_GE(n, 2) << (key >> 32) << "-" << (key & 0xffffffffu);
    const auto useAfter = edgeUse(c.surface);
    for (const auto& e : edges) {
        if (e[0] == e[1]) continue;
        EXPECT_EQ(useAfter.count(edgeKey(e[0], e[1])), 0u);
    }
}

TEST(RefineComplex, RoundsLeaveFewerBadTetsOnAThinPdlWithTheSameSurface) {
    // The thin PDL of the improver's test: TetGen under -Y leaves slivers the improver cannot
    // all mend. A refinement round splits the surface edges around them and meshes again.
    TetOptions o;
    o.radiusEdgeRatio = 2.0;
    o.repairAttempts = 0;
    o.refineRounds = 0;
    o.slivers.lookaheadDepth = 0;  // the rounds on their own (and the lookahead takes minutes here)
    o.slivers.interfacePushMm = o.slivers.outerPushMm = 0; // the surface must stay where it is
    const InterfaceComplex plc = test::thinPdlComplex(0.04, 2);
    TetStats plain, refined;
    const TetMesh a = tetrahedralize(plc, o, noProgress(), &plain);
    o.refineRounds = 2;
    const TetMesh b = tetrahedralize(plc, o, noProgress(), &refined);
    std::printf("below 10 deg: %zu without refinement, %zu after %d rounds (%zu edges split)\n", plain.belowMinDihedral,
                refined.belowMinDihedral, refined.refineRounds, refined.refinedEdges);
    ASSERT_GT(plain.belowMinDihedral, 0u);
    EXPECT_GE(refined.refineRounds, 1);
    EXPECT_GT(refined.refinedEdges, 0u);
    EXPECT_LT(refined.belowMinDihedral, plain.belowMinDihedral);
    EXPECT_EQ(measureQuality(b, 10.0).belowDihedralThreshold, refined.belowMinDihedral);
    EXPECT_TRUE(validateTetMesh(b, {}).valid());
    // The refined surface encloses the same regions.
    const auto before = test::complexVolumes(plc);
    std::map<Label, double> after;
    for (std::size_t t = 0; t < b.tets.size(); ++t) {
        const auto& e = b.tets[t];
        const auto& n = b.nodes;
        after[b.labels[t]] += (n[std::size_t(e[1])] - n[std::size_t(e[0])])
                                  .cross(n[std::size_t(e[2])] - n[std::size_t(e[0])])
                                  .dot(n[std::size_t(e[3])] - n[std::size_t(e[0])]) / 6.0;
    }
    for (const auto& [label, v] : before) EXPECT_NEAR(after.at(label), v, 1e-9 * v) << label;
}
