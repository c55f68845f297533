// Bringing the jaws of a biting scenario into contact (fe/CloseBite.h).
#include "fe/CloseBite.h"
#include "fe/FeTestMeshes.h"
#include "io/Error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace jawmesh {
namespace {

TetMesh movedBy(const TetMesh& mesh, const Vec3& offset) { return withMandibleMoved(mesh, offset); }

TEST(CloseBite, GapIsTheDistanceAlongTheBiteBetweenTheCrowns) {
    const TetMesh bite = test::twoCrownBite();  // crowns 0.5 mm apart along z
    EXPECT_NEAR(biteGapMm(bite, exteriorFaces(bite), Vec3::UnitZ()), 0.5, 1e-12);
    // Moved 0.3 mm up: 0.2 left; moved sideways off the upper crown: they never meet.
    const TetMesh closer = movedBy(bite, Vec3(0, 0, 0.3));
    EXPECT_NEAR(biteGapMm(closer, exteriorFaces(closer), Vec3::UnitZ()), 0.2, 1e-12);
    const TetMesh aside = movedBy(bite, Vec3(2.5, 0, 0));
    EXPECT_TRUE(std::isinf(biteGapMm(aside, exteriorFaces(aside), Vec3::UnitZ())));
    // Moved 0.75 mm up, the lower crown's top lies inside the upper crown: no gap to close.
    const TetMesh into = movedBy(bite, Vec3(0, 0, 0.75));
    EXPECT_EQ(biteGapMm(into, exteriorFaces(into), Vec3::UnitZ()), 0.0);
}

TEST(CloseBite, MovesOnlyTheMandibleAndRefusesSharedNodes) {
    const TetMesh bite = test::twoCrownBite();
    const TetMesh moved = movedBy(bite, Vec3(0, 0, 1));
    for (std::size_t t = 0; t < bite.tets.size(); ++t) {
        const bool mandible = bite.labels[t] == kMandibleBoneLabel || bite.labels[t] == toothLabel(24);
        for (std::int32_t n : bite.tets[t]) {
            const auto v = static_cast<std::size_t>(n);
            EXPECT_EQ(moved.nodes[v], bite.nodes[v] + (mandible ? Vec3(0, 0, 1) : Vec3::Zero()));
        }
    }
    // A node in both jaws cannot move with one of them.
    TetMesh shared = bite;
    shared.labels[0] = kMaxillaBoneLabel;  // a tet of the mandible base now claims maxilla
    EXPECT_THROW(withMandibleMoved(shared, Vec3(0, 0, 1)), Error);
}

}  // namespace
}  // namespace jawmesh
