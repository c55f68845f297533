// The tet stage's repair of an interface complex with holes (issue #27): the holes' loops
// (filters/HoleLoops.h), the local patches and lids (filters/FillSurfaceHoles.h) and the meshing of
// the repaired complex, on the voxel jaw block with faces taken out.
#include "filters/FillSurfaceHoles.h"
#include "filters/HoleLoops.h"
#include "filters/OpenRegionEdges.h"
#include "io/Error.h"
#include "tet/TetTestComplexes.h"
#include "tet/Tetrahedralize.h"
#include "tet/ValidateTetMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

using namespace jawmesh;
using namespace jawmesh::test;

namespace {

/// Takes out the two triangles of the jaw block's bottom face (z = 0, bone below nothing) over
/// the unit square [x, x + 1] x [y, y + 1].
void removeBottomSquare(InterfaceComplex& c, double x, double y) {
    std::vector<Tri> triangles;
    std::vector<std::array<Label, 2>> sides;
    for (std::size_t t = 0; t < c.surface.triangles.size(); ++t) {
        Vec3 centre = Vec3::Zero();
        bool bottom = true;
        for (const std::int32_t v : c.surface.triangles[t]) {
            centre += c.surface.vertices[std::size_t(v)] / 3.0;
            bottom = bottom && c.surface.vertices[std::size_t(v)].z() == 0.0;
        }
        if (bottom && centre.x() > x && centre.x() < x + 1 && centre.y() > y && centre.y() < y + 1) continue;
        triangles.push_back(c.surface.triangles[t]);
        sides.push_back(c.sides[t]);
    }
    ASSERT_EQ(triangles.size() + 2, c.surface.triangles.size());
    c.surface.triangles = std::move(triangles);
    c.sides = std::move(sides);
}

/// Two holes in the bone's bottom face that touch at the vertex (3, 3, 0), and one elsewhere.
InterfaceComplex jawBlockWithHoles() {
    InterfaceComplex c = complexFromVoxels(jawBlockScene());
    removeBottomSquare(c, 2, 2);
    removeBottomSquare(c, 3, 3);
    removeBottomSquare(c, 10, 5);
    return c;
}

/// A square of bone/outside triangles 0.5 mm below the block, every edge open: the one face of a
/// region's box that an extraction kept (a lid, filters/HoleFlap.h).
void addLid(InterfaceComplex& c) {
    const auto base = std::int32_t(c.surface.vertices.size());
    for (const Vec3& p : {Vec3(5, 5, -0.5), Vec3(6, 5, -0.5), Vec3(6, 6, -0.5), Vec3(5, 6, -0.5)}) c.surface.vertices.push_back(p);
    c.surface.triangles.push_back({base, base + 1, base + 2});
    c.surface.triangles.push_back({base, base + 2, base + 3});
    c.sides.push_back({kOutsideLabel, kMandibleBoneLabel});
    c.sides.push_back({kOutsideLabel, kMandibleBoneLabel});
}

double tetVolume(const TetMesh& m, std::size_t t) {
    const Tet& e = m.tets[t];
    const Vec3& a = m.nodes[std::size_t(e[0])];
    return (m.nodes[std::size_t(e[1])] - a).dot((m.nodes[std::size_t(e[2])] - a).cross(m.nodes[std::size_t(e[3])] - a)) / 6.0;
}

}  // namespace

TEST(HoleRepair, LoopsTouchingAtAVertexAreSplitThere) {
    const HoleLoops found = holeLoops(jawBlockWithHoles());
    EXPECT_EQ(found.strayEdges, 0u);
    ASSERT_EQ(found.loops.size(), 3u);
    for (const HoleLoop& loop : found.loops) {
        EXPECT_EQ(loop.pair, (std::array<Label, 2>{kOutsideLabel, kMandibleBoneLabel}));
        EXPECT_EQ(loop.vertices.size(), 4u);
        EXPECT_EQ(std::set<std::int32_t>(loop.vertices.begin(), loop.vertices.end()).size(), 4u);
    }
}

TEST(HoleRepair, PatchesCloseTheHolesAndALidIsTakenOut) {
    InterfaceComplex c = jawBlockWithHoles();
    addLid(c);
    const HoleFillStats stats = fillSurfaceHoles(c);
    EXPECT_TRUE(openRegionEdges(c).empty());
    EXPECT_TRUE(stats.left.empty());
    ASSERT_EQ(stats.filled.size(), 4u);
    EXPECT_EQ(stats.trianglesAdded(), 6u);    // two per square hole
    EXPECT_EQ(stats.trianglesRemoved(), 2u);  // the lid
    EXPECT_EQ(stats.verticesAdded(), 0u);
    EXPECT_NEAR(stats.largestHoleMm(), std::sqrt(2.0), 1e-12);
    // The patches lie in the bottom face and are wound as the sheet: the block's volumes are back.
    const std::map<Label, double> want = voxelVolumes(jawBlockScene()), got = complexVolumes(c);
    for (const auto& [label, volume] : want) EXPECT_NEAR(got.at(label), volume, 1e-9 * volume) << labelName(label);
}

TEST(HoleRepair, TheTetStageRepairsAndMeshesWithExactVolumes) {
    InterfaceComplex c = jawBlockWithHoles();
    addLid(c);
    TetOptions o;
    o.boneEdgeMm = 2.0;
    o.toothEdgeMm = 1.0;
    o.pdlEdgeMm = 0.6;
    TetStats stats;
    const TetMesh m = tetrahedralize(c, o, noProgress(), &stats);
    EXPECT_EQ(stats.holeRepair.filled.size(), 4u);
    EXPECT_EQ(stats.holeRepair.trianglesAdded(), 6u);
    EXPECT_TRUE(validateTetMesh(m, {24, 25}).valid());
    std::map<Label, double> got;
    for (std::size_t t = 0; t < m.tets.size(); ++t) got[m.labels[t]] += tetVolume(m, t);
    for (const auto& [label, volume] : voxelVolumes(jawBlockScene())) EXPECT_NEAR(got.at(label), volume, 1e-9 * volume) << labelName(label);
    EXPECT_GE(stats.minDihedralDeg, 10.0);
}

TEST(HoleRepair, OpenEdgesOnNoLoopKeepTheClearError) {
    // Two triangles hinged on one edge, far from the block, of two different label pairs: four
    // labels open at the hinge, chains that do not close. Nothing local to patch.
    InterfaceComplex c = complexFromVoxels(jawBlockScene());
    const auto base = std::int32_t(c.surface.vertices.size());
    for (const Vec3& p : {Vec3(30, 0, 0), Vec3(30, 1, 0), Vec3(31, 0, 0), Vec3(30, 0, 1)}) c.surface.vertices.push_back(p);
    c.surface.triangles.push_back({base, base + 1, base + 2});
    c.sides.push_back({kMandibleBoneLabel, toothLabel(24)});
    c.surface.triangles.push_back({base, base + 1, base + 3});
    c.sides.push_back({kOutsideLabel, pdlLabel(25)});
    try {
        tetrahedralize(c, TetOptions{});
        FAIL() << "no error for a complex with holes that cannot be repaired";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the interface surface has holes"), std::string::npos) << e.what();
    }
}
