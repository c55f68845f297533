// Tipping and biting setups on a block with known geometry: fixed base, load patches on the labial
// crown, consistent nodal forces (linear and quadratic), shared Tet10 mid-edge nodes.
#include "fe/ConsistentNodalForces.h"
#include "fe/ExteriorFaces.h"
#include "fe/FeTestMeshes.h"
#include "fe/QuadraticTets.h"
#include "fe/Scenario.h"
#include "io/Error.h"
#include "tet/GridTetMesh.h"

#include <gtest/gtest.h>

#include <set>

namespace jawmesh {
namespace {

TEST(TippingScenario, FixesTheBaseAndLoadsEachLabialCrownOverAPatch) {
    const TetMesh mesh = test::gridJawBlock();
    const FeScenario s = tippingScenario(mesh, test::gridJawBlockAxes());
    ASSERT_EQ(s.fixed.size(), 1u);
    EXPECT_EQ(s.fixed[0].name, "fixed_base_mandible");
    EXPECT_GT(s.fixed[0].nodes.size(), 100u);
    EXPECT_FALSE(s.fixed[0].faces.empty());
    for (std::int32_t v : s.fixed[0].nodes) EXPECT_LE(mesh.nodes[static_cast<std::size_t>(v)].z(), 3.0 + 1e-9);
    bool bottomFixed = false;
    for (std::int32_t v : s.fixed[0].nodes) bottomFixed |= mesh.nodes[static_cast<std::size_t>(v)].z() == 0.0;
    EXPECT_TRUE(bottomFixed);

    ASSERT_EQ(s.loads.size(), 2u);
    for (const SurfaceLoad& l : s.loads) {
        SCOPED_TRACE(l.name);
        EXPECT_GE(l.faces.size(), 4u);  // a patch, never one triangle
        EXPECT_NEAR(l.totalForceN.norm(), 1.0, 1e-12);
        EXPECT_NEAR(l.totalForceN.y(), 1.0, 1e-12);  // lingual = +y here
        double area = 0;
        for (const Tri& t : l.faces) {
            area += triangleArea(mesh.nodes, t);
            EXPECT_NEAR(triangleNormal(mesh.nodes, t).dot(-Vec3::UnitY()), 1.0, 1e-9);  // labial crown face
            for (std::int32_t v : t) {
                const Vec3& p = mesh.nodes[static_cast<std::size_t>(v)];
                EXPECT_NEAR(p.y(), 1.5, 1e-9);
                EXPECT_GE(p.z(), 4.0 - 1e-9);  // crown, above the crest
            }
        }
        EXPECT_NEAR(area, l.areaMm2, 1e-12);
        const Vec3& ref = mesh.nodes[static_cast<std::size_t>(l.referenceNode)];
        EXPECT_NEAR(ref.z(), 5.5, 1e-9);
        EXPECT_NEAR(ref.x(), l.unn == 24 ? 3.0 : 7.0, 1e-9);
    }
}

TEST(TippingScenario, SkipsTeethWithoutAxesAndFailsWhenNoneIsLoadable) {
    const TetMesh mesh = test::gridJawBlock();
    auto axes = test::gridJawBlockAxes();
    axes.erase(25);
    const FeScenario s = tippingScenario(mesh, axes);
    ASSERT_EQ(s.loads.size(), 1u);
    EXPECT_EQ(s.loads[0].unn, 24);
    ASSERT_FALSE(s.notes.empty());
    EXPECT_NE(s.notes[0].find("25"), std::string::npos);
    EXPECT_THROW(tippingScenario(mesh, {}), Error);
}

TEST(ConsistentNodalForces, SumToTheResultantAndFollowTheElementOrder) {
    const TetMesh mesh = test::gridJawBlock();
    const FeScenario s = tippingScenario(mesh, test::gridJawBlockAxes());
    EdgeMidNodes mids;
    const MixedTetMesh quadratic = quadraticTetMesh(mesh, &mids);
    for (const SurfaceLoad& l : s.loads) {
        Vec3 sum = Vec3::Zero();
        const auto linear = consistentNodalForces(l, mesh.nodes);
        EXPECT_GT(linear.size(), 4u);
        for (const auto& [node, f] : linear) {
            EXPECT_LT(node, static_cast<std::int32_t>(mesh.nodes.size()));
            sum += f;
        }
        EXPECT_NEAR((sum - l.totalForceN).norm(), 0.0, 1e-12);
        sum.setZero();
        for (const auto& [node, f] : consistentNodalForces(l, quadratic.nodes, &mids)) {
            EXPECT_GE(node, static_cast<std::int32_t>(mesh.nodes.size()));  // only mid-edge nodes load a Tet10 face
            sum += f;
        }
        EXPECT_NEAR((sum - l.totalForceN).norm(), 0.0, 1e-12);
    }
}

TEST(QuadraticTets, MidEdgeNodesAreSharedAndAtEdgeMidpoints) {
    const TetMesh mesh = test::gridJawBlock();
    EdgeMidNodes mids;
    const MixedTetMesh q = quadraticTetMesh(mesh, &mids);
    std::set<std::uint64_t> edges;
    for (const Tet& t : mesh.tets)
        for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) edges.insert(edgeKey(t[static_cast<std::size_t>(a)], t[static_cast<std::size_t>(b)]));
    EXPECT_EQ(q.nodes.size(), mesh.nodes.size() + edges.size());
    EXPECT_EQ(mids.size(), edges.size());
    ASSERT_EQ(q.tets.size(), mesh.tets.size());
    for (std::size_t t = 0; t < q.tets.size(); ++t)
        for (std::size_t k = 0; k < 6; ++k) {
            const Vec3 mid = 0.5 * (q.nodes[static_cast<std::size_t>(q.tets[t][static_cast<std::size_t>(kGmshTet10Edges[k][0])])] +
                                    q.nodes[static_cast<std::size_t>(q.tets[t][static_cast<std::size_t>(kGmshTet10Edges[k][1])])]);
            ASSERT_NEAR((q.nodes[static_cast<std::size_t>(q.tets[t][4 + k])] - mid).norm(), 0.0, 1e-12);
        }
    const Tet10 abaqus = abaqusOrderFromGmsh(q.tets[0]);
    EXPECT_EQ(abaqus[7], mids.at(edgeKey(q.tets[0][0], q.tets[0][3])));
    EXPECT_EQ(abaqus[8], mids.at(edgeKey(q.tets[0][1], q.tets[0][3])));
    EXPECT_EQ(abaqus[9], mids.at(edgeKey(q.tets[0][2], q.tets[0][3])));
}

TEST(BitingScenario, FixesTheMaxillaTopAndPushesTheMandibleBaseUp) {
    // Two slabs: mandible z in [0, 5], maxilla z in [6, 14] (a gap between them), no teeth.
    const TetMesh mesh = test::withoutOutside(test::gridTetMesh(8, 4, 28, 0.5, [](const Vec3& p) -> Label {
        return p.z() < 5 ? kMandibleBoneLabel : p.z() > 6 ? kMaxillaBoneLabel : kOutsideLabel;
    }));
    const FeScenario s = bitingScenario(mesh);
    EXPECT_TRUE(s.contact);
    ASSERT_EQ(s.fixed.size(), 2u);
    EXPECT_FALSE(s.fixed[0].nodes.empty());
    for (std::int32_t v : s.fixed[0].nodes) EXPECT_GE(mesh.nodes[static_cast<std::size_t>(v)].z(), 8.0 - 1e-9);
    EXPECT_FALSE(s.fixed[1].nodes.empty());
    for (std::int32_t v : s.fixed[1].nodes) EXPECT_LE(mesh.nodes[static_cast<std::size_t>(v)].z(), 3.0 + 1e-9);
    EXPECT_TRUE(s.fixed[0].fixedDofs[2]);
    EXPECT_FALSE(s.fixed[1].fixedDofs[2]);  // mandible base free vertically
    EXPECT_TRUE(s.fixed[1].fixedDofs[0] && s.fixed[1].fixedDofs[1]);
    ASSERT_EQ(s.loads.size(), 1u);
    EXPECT_NEAR(s.loads[0].totalForceN.z(), 200.0, 1e-9);
    EXPECT_THROW(bitingScenario(test::gridJawBlock()), Error);
}

}  // namespace
}  // namespace jawmesh
