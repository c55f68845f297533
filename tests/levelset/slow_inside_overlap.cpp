// The heavy-overlap refusal (levelset/InsideOverlap.h) must not fire on real teeth: every pair of
// the shared cases' teeth (OpenMandible 18..31, p26 maxilla 1..15; neighbours in contact) shares
// less than kHeavyToothOverlapFraction of the smaller tooth, while a tooth against a copy of itself
// moved by a quarter of its width shares most of it.
#include "io/Case.h"
#include "levelset/InsideOverlap.h"
#include "levelset/MeshToLevelSet.h"
#include "support/TestData.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace jawmesh {
namespace {

void checkCase(const std::string& dir) {
    const double voxel = 0.1;
    const JawSurfaces s = loadJaw(discoverCase(dir).jaws.front());
    std::map<int, openvdb::FloatGrid::Ptr> teeth;
    for (const auto& [unn, mesh] : s.teeth) teeth[unn] = meshToLevelSet(mesh, voxel);
    double worst = 0;
    int worstA = 0, worstB = 0;
    for (auto a = teeth.begin(); a != teeth.end(); ++a)
        for (auto b = std::next(a); b != teeth.end(); ++b) {
            const double shared = insideOverlapFraction(*a->second, *b->second);
            if (shared > worst) {
                worst = shared;
                worstA = a->first;
                worstB = b->first;
            }
        }
    std::printf("[overlap] %s: largest shared share %.4f (teeth %d and %d)\n", dir.c_str(), worst, worstA, worstB);
    EXPECT_LT(worst, kHeavyToothOverlapFraction);

    const auto& [unn, mesh] = *s.teeth.begin();
    SurfaceMesh moved = mesh;
    const BBox box = boundingBox(mesh);
    for (Vec3& v : moved.vertices) v.x() += 0.25 * box.size().x();
    EXPECT_GT(insideOverlapFraction(*teeth.at(unn), *meshToLevelSet(moved, voxel)), kHeavyToothOverlapFraction)
        << "tooth " << unn << " against itself moved by a quarter of its width";
}

TEST(SlowInsideOverlap, RealTeethInContactStayBelowTheRefusalThreshold) {
    for (const char* name : {"openmandible", "p26-maxilla-teeth"}) {
        const std::string dir = test::sharedData(name);
        JAWMESH_REQUIRE_SHARED(dir);
        SCOPED_TRACE(name);
        checkCase(dir);
    }
}

}  // namespace
}  // namespace jawmesh
