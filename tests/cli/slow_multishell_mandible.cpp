// Issue #27 item 3: the shared mandible's teeth as segmentations export them.
//  - Multi-shell (a micro-CT export): each tooth the plain concatenation of overlapping closed
//    shells, not welded: the tooth itself, a "pulp" shell 1 mm inside it and an "enamel" cap over
//    the crown (the tooth cut 3 mm under its highest point), the last two from the tooth's signed
//    distance, so the cap's crown and the tooth's are near-coincident faces of two shells. The union
//    of the shells is the tooth, so the run must meet the clean run's figures against the clean teeth.
//  - Staircase: each tooth as its voxels of 0.2 mm, unsmoothed (tests/support/VoxelStaircase.h),
//    judged against that staircase, as the user gave it.
// The multi-shell run is part of the slow set (CI): a whole-mandible run takes about two minutes
// since issue #22 (117 s for the test at 4fe6e62). The staircase test is disabled (below); it runs
// with JAWMESH_DIRTY_TEETH_TEST=1 and --gtest_also_run_disabled_tests (build/tests/slow_cli).
#include "io/MeshIO.h"
#include "levelset/Csg.h"
#include "levelset/LevelSetSurface.h"
#include "levelset/MeshToLevelSet.h"
#include "support/DirtySurfaces.h"
#include "support/TestData.h"
#include "support/VoxelStaircase.h"
#include "support_CliRun.h"
#include "support_RunChecks.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

/// The tooth, a pulp shell kPulpDepthMm inside it and an enamel cap over its crown (the tooth cut
/// kCapDepthMm under its highest point), concatenated, not welded. Both extra shells are surfaces
/// of the tooth's own signed distance: the pulp its -1 mm level, the cap its intersection with a
/// box over the cut (levelset/Csg.h), so the cap's crown lies on the tooth's within the
/// extraction's error (near-coincident faces of two shells) and the union of the three is the tooth.
SurfaceMesh multiShellTooth(const SurfaceMesh& tooth) {
    constexpr double kVoxelMm = 0.1, kPulpDepthMm = 1.0, kCapDepthMm = 3.0;
    const openvdb::FloatGrid::Ptr field = meshToLevelSet(tooth, kVoxelMm, kPulpDepthMm / kVoxelMm + 3);
    const SurfaceMesh pulp = extractLevelSetSurface(*field, -kPulpDepthMm);
    openvdb::math::BBox<openvdb::Vec3s> box;
    for (const Vec3& v : tooth.vertices) box.expand(openvdb::Vec3s(float(v.x()), float(v.y()), float(v.z())));
    box.min() -= openvdb::Vec3s(1.0f);
    box.max() += openvdb::Vec3s(1.0f);
    box.min().z() = box.max().z() - float(1.0 + kCapDepthMm);  // the cut, kCapDepthMm under the top
    const openvdb::FloatGrid::Ptr above = openvdb::tools::createLevelSetBox<openvdb::FloatGrid>(box, field->transform(), 3.0f);
    const SurfaceMesh cap = extractLevelSetSurface(*csgIntersection(*field, *above), 0.0);
    return test::concatenated(test::concatenated(tooth, pulp), cap);
}

/// Writes the shared mandible as a case in `dir`/case with every tooth replaced by dirty(tooth);
/// runs `jawmesh run` on it into `dir`/out and returns the clean case's teeth.
std::vector<int> runWithDirtyTeeth(const fs::path& dir, const std::function<SurfaceMesh(const SurfaceMesh&)>& dirty) {
    const std::string clean = test::sharedData("openmandible/input/mandible");
    const fs::path input = dir / "case" / "input" / "mandible";
    fs::create_directories(input / "teeth");
    fs::copy(fs::path(clean) / "bone", input / "bone", fs::copy_options::recursive);
    const std::vector<int> teeth = test::teethIn(clean + "/teeth");
    EXPECT_EQ(teeth.size(), 14u);
    for (const int unn : teeth) {
        const std::string name = "tooth_" + std::to_string(unn) + ".stl";
        writeSurface(dirty(readSurface(clean + "/teeth/" + name)), (input / "teeth" / name).string());
    }
    const test::CliResult r = test::runJawmesh("-q run " + (dir / "case").string() + " -o " + (dir / "out").string() + " --jaw mandible",
                                               dir / "run.log");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return teeth;
}

constexpr const char* kRunOnRequest = "set JAWMESH_DIRTY_TEETH_TEST=1 (a whole-mandible run)";

TEST(SlowDirtyMandible, MultiShellTeethMeshEndToEnd) {
    JAWMESH_REQUIRE_SHARED(test::sharedData("openmandible/input/mandible"));
    const fs::path dir = test::scratchDir("multishell-mandible");
    const std::vector<int> teeth = runWithDirtyTeeth(dir, [](const SurfaceMesh& tooth) {
        const SurfaceMesh shells = multiShellTooth(tooth);
        EXPECT_GT(shells.triangles.size(), 2 * tooth.triangles.size());
        return shells;
    });
    if (HasFailure()) return;
    // against the clean teeth: the union of each tooth's shells
    const std::string clean = test::sharedData("openmandible/input/mandible");
    test::expectRunMeetsTargets(test::measureRun((dir / "out" / "mandible").string(), clean, "mandible", teeth), teeth);
}

// Disabled, the open item of #27 (docs/BENCHMARKS.md sessions 30, 34 and 42): the run meets 10 deg
// and the PDL figures, but the 0.2 mm steps (up to 0.1 mm off the tooth they sample), kept within
// the teeth's 0.02 mm bound, make 1.23 M tets (issue #5 allows 800 k), and one tooth lies 0.153 mm
// from its staircase (0.15 allowed, of which the root's designed erosion takes 0.1). Following the
// steps less closely (0.04-0.05 mm bounds: 566 k tets) puts the roots 0.150-0.163 mm off; smoothing
// them away (as a 0.2 mm label map is smoothed: 841 k tets) puts them 0.20-0.27 mm off the teeth.
TEST(SlowDirtyMandible, DISABLED_StaircaseTeethMeshEndToEnd) {
    if (!std::getenv("JAWMESH_DIRTY_TEETH_TEST")) GTEST_SKIP() << kRunOnRequest;
    JAWMESH_REQUIRE_SHARED(test::sharedData("openmandible/input/mandible"));
    const fs::path dir = test::scratchDir("staircase-mandible");
    const std::vector<int> teeth = runWithDirtyTeeth(dir, [](const SurfaceMesh& tooth) { return test::voxelStaircase(tooth, 0.2); });
    if (HasFailure()) return;
    // against the staircase teeth the run was given
    test::expectRunMeetsTargets(test::measureRun((dir / "out" / "mandible").string(), (dir / "case" / "input" / "mandible").string(),
                                                 "mandible", teeth),
                                teeth);
}

}  // namespace
}  // namespace jawmesh
