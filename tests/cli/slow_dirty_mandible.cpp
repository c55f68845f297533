// Issue #27: the shared mandible with about 20 holes punched into its bone surface (clusters of
// faces removed, 1-3 mm wide, as a segmentation export with gaps leaves them) meshes end to end.
// The level sets patch the holes (levelset/CloseHoles.h) so the bone's distance band runs across
// them; the run must then meet the figures of a clean run, measured against the clean input
// surfaces. Until session 16 it failed in the tet stage ("a region boundary is open" between tooth
// 31 and the outside): winding numbers alone closed the holes with a sign jump and no distance
// band, carving made no PDL there and left a sliver of outside between root and socket
// (docs/DESIGN.md, Known pitfalls).
#include "io/MeshIO.h"
#include "levelset/support_meshtolevelset.h"
#include "support/TestData.h"
#include "support_CliRun.h"
#include "support_RunChecks.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

TEST(SlowDirtyMandible, BoneWithPunchedHolesMeshesEndToEnd) {
    const std::string clean = test::sharedData("openmandible/input/mandible");
    JAWMESH_REQUIRE_SHARED(clean);
    const fs::path dir = test::scratchDir("dirty-mandible");
    const fs::path input = dir / "case" / "input" / "mandible";
    fs::create_directories(input / "bone");
    fs::copy(fs::path(clean) / "teeth", input / "teeth", fs::copy_options::recursive);
    const SurfaceMesh bone = readSurface(clean + "/bone/mandible.stl");
    std::vector<std::pair<Vec3, double>> holes;
    const SurfaceMesh holey = test::punchHoles(bone, 20, 0.5, 1.5, 11, &holes);  // radii 0.5-1.5 mm: holes 1-3 mm wide
    ASSERT_LT(holey.triangles.size(), bone.triangles.size());
    writeSurface(holey, (input / "bone" / "mandible.stl").string());

    const fs::path out = dir / "out";
    const test::CliResult r = test::runJawmesh("-q run " + (dir / "case").string() + " -o " + out.string() + " --jaw mandible",
                                               dir / "run.log");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::vector<int> teeth = test::teethIn(clean + "/teeth");
    ASSERT_EQ(teeth.size(), 14u);
    // A patch cannot know the surface the punching took away: the flat one over the 2 mm hole on
    // the ridge at (115.1, 108.6, 57.7) lies 0.78 mm off it (session 16). Away from the holes (their
    // radius + 0.5 mm) the bone meets #5's 0.25 mm; over them, within the sag of a 3 mm patch.
    constexpr double kPatchSagMm = 1.0;
    test::expectRunMeetsTargets(test::measureRun((out / "mandible").string(), clean, "mandible", teeth), teeth, kPatchSagMm);
    for (auto& hole : holes) hole.second += 0.5;
    const double awayMm = test::boneHausdorffAwayFrom((out / "mandible").string(), clean, "mandible", holes);
    std::printf("bone Hausdorff away from the holes: %.3f mm\n", awayMm);
    EXPECT_LE(awayMm, 0.25);
    std::printf("bone: %zu of %zu triangles kept after punching\n", holey.triangles.size(), bone.triangles.size());
}

}  // namespace
}  // namespace jawmesh
