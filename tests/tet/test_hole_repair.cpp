// The tet stage's repair of an interface complex with holes (issue #27): the holes' loops
// (filters/HoleLoops.h), the local patches and lids (filters/FillSurfaceHoles.h) and the meshing of
// the repaired complex, on the voxel jaw block with faces taken out.
#include "filters/FillSurfaceHoles.h"
#include "filters/HoleLoops.h"
#include "filters/OpenRegionEdges.h"
#include "filters/PatchWedgeOpening.h"
#include "filters/RegionWedges.h"
#include "filters/SelfIntersections.h"
#include "filters/TriangleGeometry.h"
#include "io/Error.h"
#include "tet/HolePoints.h"
#include "tet/TetTestComplexes.h"
#include "tet/Tetrahedralize.h"
#include "tet/ValidateTetMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

/// A flat square pyramid of bone, its top face (the unit square at z = 0) missing and its apex
/// 0.05 mm below: a flat patch meets the walls at a region wedge of atan(0.05 / 0.5) = 5.71 deg.
/// With `speck`, a tetrahedron of bone 0.01 mm across floats 0.02 mm above the hole's centre.
InterfaceComplex flatPyramidWithOpenTop(bool speck) {
    InterfaceComplex c;
    c.surface.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, -0.05}};
    for (std::int32_t i = 0; i < 4; ++i) c.surface.triangles.push_back({(i + 1) % 4, i, 4});  // outward: down and out
    if (speck) {
        const Vec3 centre(0.5, 0.5, 0.02);
        const double s = 0.005;
        for (const Vec3& d : {Vec3(s, s, s), Vec3(s, -s, -s), Vec3(-s, s, -s), Vec3(-s, -s, s)}) c.surface.vertices.push_back(centre + d);
        for (const Tri& t : {Tri{5, 6, 7}, Tri{5, 8, 6}, Tri{5, 7, 8}, Tri{6, 8, 7}}) c.surface.triangles.push_back(t);
    }
    c.sides.assign(c.surface.triangles.size(), {kOutsideLabel, kMandibleBoneLabel});
    return c;
}

// A patch that would fold sharply against the sheet (a region wedge under kHoleMinWedgeDeg, whose
// tets could only be slivers) gives way to a fan raised along the loop's normal, unless that fan
// would sweep over another piece of the surface.
TEST(HoleRepair, SharpWedgeOpensWithARaisedFanThatSweepsNothing) {
    const double flatDeg = std::atan(0.1) * 180 / M_PI;
    {
        InterfaceComplex c = flatPyramidWithOpenTop(false);
        ASSERT_GT(complexVolumes(c).count(kMandibleBoneLabel), 0u);
        const HoleFillStats stats = fillSurfaceHoles(c);
        ASSERT_EQ(stats.filled.size(), 1u);
        EXPECT_EQ(stats.filled[0].how, HoleRepair::RaisedFan);
        EXPECT_TRUE(openRegionEdges(c).empty());
        EXPECT_GE(measureRegionWedges(c, kHoleMinWedgeDeg).smallestDeg, kHoleMinWedgeDeg);
        // The bone gained the raised fan's pyramid over the unit square: a third of its height.
        const double apexHeight = c.surface.vertices.back().z();
        EXPECT_GT(apexHeight, 0.0);
        EXPECT_NEAR(complexVolumes(c).at(kMandibleBoneLabel), 0.05 / 3 + apexHeight / 3, 1e-12);
    }
    {
        InterfaceComplex c = flatPyramidWithOpenTop(true);
        const HoleFillStats stats = fillSurfaceHoles(c);
        ASSERT_EQ(stats.filled.size(), 1u);
        EXPECT_EQ(stats.filled[0].how, HoleRepair::EarClipping);  // every raised fan would cover the speck
        EXPECT_TRUE(openRegionEdges(c).empty());
        EXPECT_NEAR(measureRegionWedges(c, kHoleMinWedgeDeg).smallestDeg, flatDeg, 1e-9);
    }
}

// A repair triangle folding sharply against the sheet (the flat cap of the pyramid, as a patch cut
// from tets may lie) is bumped: a fan around a point lifted off it, clean, the wedge opened, the
// bone grown by the tets the bumps add; never over another piece of the surface.
TEST(HoleRepair, SharpRepairTrianglesAreBumpedWhereTheBumpSweepsNothing) {
    for (const bool speck : {false, true}) {
        SCOPED_TRACE(speck ? "speck over the first cap triangle" : "no speck");
        InterfaceComplex c = flatPyramidWithOpenTop(false);
        if (speck) {  // 0.02 mm over (0.7, 0.3), inside the first cap triangle's outline
            InterfaceComplex withSpeck = flatPyramidWithOpenTop(true);
            for (Vec3& v : withSpeck.surface.vertices)
                if (v.z() > 0) v += Vec3(0.2, -0.2, 0);
            c = withSpeck;
        }
        const std::size_t given = c.surface.triangles.size();
        c.surface.triangles.push_back({0, 1, 2});  // the cap, wound up and out like the walls' outside
        c.surface.triangles.push_back({0, 2, 3});
        c.sides.resize(c.surface.triangles.size(), {kOutsideLabel, kMandibleBoneLabel});
        ASSERT_TRUE(openRegionEdges(c).empty());
        const double volumeBefore = complexVolumes(c).at(kMandibleBoneLabel);
        std::vector<char> bumpable(c.surface.triangles.size(), 0);
        bumpable[given] = bumpable[given + 1] = 1;
        const PatchWedgeStats stats = openPatchWedges(c, bumpable, kHoleMinWedgeDeg);
        EXPECT_NEAR(stats.smallestWedgeBeforeDeg, std::atan(0.1) * 180 / M_PI, 1e-9);
        EXPECT_TRUE(openRegionEdges(c).empty());
        EXPECT_TRUE(findSelfIntersections(c.surface).clean());
        EXPECT_GT(complexVolumes(c).at(kMandibleBoneLabel), volumeBefore);
        EXPECT_EQ(bumpable.size(), c.surface.triangles.size());
        if (speck) {  // the first cap triangle stays as it was: every bump of it covers the speck or cuts the walls
            EXPECT_EQ(c.surface.triangles[given], (Tri{0, 1, 2}));
            EXPECT_GE(stats.bumps, 1u);
            EXPECT_EQ(stats.smallestWedgeAfterDeg, stats.smallestWedgeBeforeDeg);  // its wedge at the wall
        } else {
            EXPECT_GE(stats.bumps, 2u);
            EXPECT_GE(stats.smallestWedgeAfterDeg, kHoleMinWedgeDeg);
        }
    }
}

/// An octahedron flattened to a disc, every triangle a repair's: equator +x, +y, -x, -y and apexes
/// p = (0.45, 0.45, +0.005), q = (0.45, 0.45, -0.005) off-centre, so the two sheets meet at the
/// equator edge +x +y at a fin of 2 atan(0.005 / 0.0707) = 8.1 degrees (sharper still at the far
/// edges). With `speck`, a tetrahedron of bone 0.0006 mm across at (0.6, 0.38, 0), inside the tet
/// that flipping the edge +x +y would sweep.
InterfaceComplex flatOctahedron(bool speck) {
    InterfaceComplex c;
    const double h = 0.005;
    c.surface.vertices = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0.45, 0.45, h}, {0.45, 0.45, -h}};
    for (std::int32_t i = 0; i < 4; ++i) {
        c.surface.triangles.push_back({i, (i + 1) % 4, 4});
        c.surface.triangles.push_back({(i + 1) % 4, i, 5});
    }
    if (speck) {
        const double s = 0.0003;
        for (const Vec3& d : {Vec3(s, s, s), Vec3(s, -s, -s), Vec3(-s, s, -s), Vec3(-s, -s, s)})
            c.surface.vertices.push_back(Vec3(0.6, 0.38, 0.0) + d);
        for (const Tri& t : {Tri{6, 7, 8}, Tri{6, 9, 7}, Tri{6, 8, 9}, Tri{7, 9, 8}}) c.surface.triangles.push_back(t);
    }
    c.sides.assign(c.surface.triangles.size(), {kOutsideLabel, kMandibleBoneLabel});
    return c;
}

bool hasEdge(const InterfaceComplex& c, std::int32_t a, std::int32_t b) {
    return std::any_of(c.surface.triangles.begin(), c.surface.triangles.end(),
                       [&](const Tri& t) { return std::count(t.begin(), t.end(), a) && std::count(t.begin(), t.end(), b); });
}

// Two repair triangles folded onto each other (a fin) have their shared edge flipped, the complex
// staying closed and clean; never when the flip would sweep over another piece of the surface.
TEST(HoleRepair, FinsOfTheRepairAreFlippedWhereTheFlipSweepsNothing) {
    for (const bool speck : {false, true}) {
        SCOPED_TRACE(speck ? "speck in the fin" : "no speck");
        InterfaceComplex c = flatOctahedron(speck);
        std::vector<char> repair(c.surface.triangles.size(), 0);
        std::fill(repair.begin(), repair.begin() + 8, 1);
        const PatchWedgeStats stats = openPatchWedges(c, repair, kHoleMinWedgeDeg);
        EXPECT_GE(stats.flips, 1u);  // a far edge, with the speck
        EXPECT_TRUE(openRegionEdges(c).empty());
        EXPECT_TRUE(findSelfIntersections(c.surface).clean());
        EXPECT_EQ(hasEdge(c, 0, 1), speck);  // +x +y flipped only where nothing lies in the fin
        EXPECT_TRUE(hasEdge(c, 4, 5));       // the first flip's new edge p q
    }
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

/// The jaw block with the 3 x 3 squares of its bottom face at [9, 12] x [4, 7] taken out: a hole
/// whose loop has 12 edges.
InterfaceComplex jawBlockWithWideHole() {
    InterfaceComplex c = complexFromVoxels(jawBlockScene());
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) removeBottomSquare(c, 9 + i, 4 + j);
    return c;
}

TEST(HoleRepair, PointsThroughAHoleClearTheSurfaceAndFillItsBall) {
    const InterfaceComplex open = jawBlockWithWideHole();
    InterfaceComplex patched = open;
    const HoleFillStats found = fillSurfaceHoles(patched);  // only the hole's record is used
    ASSERT_EQ(found.filled.size(), 1u);
    const FilledHole& hole = found.filled.front();
    ASSERT_EQ(hole.boundaryEdges, 12u);
    EXPECT_TRUE(pointsInHoles(open.surface, {}).empty());
    const std::vector<Vec3> through = pointsInHoles(open.surface, {hole});
    const double spacing = kHolePointSpacing * M_PI * hole.diameterMm / double(hole.boundaryEdges);
    const double radius = 0.5 * hole.diameterMm + 2.0 * spacing;
    ASSERT_FALSE(through.empty());
    std::size_t below = 0, above = 0;
    for (const Vec3& p : through) {
        EXPECT_LE((p - hole.centre).norm(), radius + 1e-12);
        double nearest2 = std::numeric_limits<double>::infinity();
        for (const Tri& t : open.surface.triangles)
            nearest2 = std::min(nearest2, squaredDistanceToTriangle(p, open.surface.vertices[std::size_t(t[0])],
                                                                    open.surface.vertices[std::size_t(t[1])], open.surface.vertices[std::size_t(t[2])]));
        EXPECT_GE(std::sqrt(nearest2), 0.5 * spacing - 1e-12) << p.transpose();
        below += p.z() < 0;
        above += p.z() > 0;
    }
    // Through the hole: points on both sides of the face, and the lattice's centre in the opening.
    EXPECT_GT(below, 0u);
    EXPECT_GT(above, 0u);
    EXPECT_TRUE(std::any_of(through.begin(), through.end(), [](const Vec3& p) {
        return std::abs(p.z()) < 1e-12 && p.x() > 9 && p.x() < 12 && p.y() > 4 && p.y() < 7;
    }));
    EXPECT_EQ(pointsInHoles(open.surface, {hole}), through);  // deterministic

    // A loop of very many short edges: the lattice stays kMaxHoleLatticeSpans across the hole.
    FilledHole fine = hole;
    fine.boundaryEdges = 100000;
    const std::vector<Vec3> capped = pointsInHoles(open.surface, {fine});
    const double cappedSpacing = hole.diameterMm / kMaxHoleLatticeSpans;
    EXPECT_GT(capped.size(), through.size());
    EXPECT_LE(capped.size(), std::size_t(37 * 37 * 37));
    for (const Vec3& p : capped) EXPECT_LE((p - hole.centre).norm(), 0.5 * hole.diameterMm + 2.0 * cappedSpacing + 1e-12);
    // Many such holes: whole lattices until the next would pass kMaxHolePoints.
    const std::vector<Vec3> many = pointsInHoles(open.surface, std::vector<FilledHole>(1000, fine));
    EXPECT_LE(many.size(), kMaxHolePoints);
    EXPECT_EQ(many.size() % capped.size(), 0u);
    EXPECT_GT(many.size() + capped.size(), kMaxHolePoints);
}
