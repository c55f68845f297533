// The worked level-set editing example (examples/edit_levelsets): carve the 2-tooth phantom,
// remove tooth 24 with the example program, resume `jawmesh run --from-vdb` on the edited grids.
// The edited mesh must be valid, without tooth 24 and its PDL, with the socket left empty and the
// rest (bone, tooth 25, PDL 25) as in the run from the unedited grids.
#include "io/GmshReader.h"
#include "tet/RegionSurfaces.h"
#include "support/TestData.h"
#include "support_CliRun.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

std::map<Label, double> volumeByLabel(const TetMesh& m) {
    std::map<Label, double> v;
    for (const auto& [label, surface] : regionSurfaces(m)) v[label] = signedVolume(surface);
    return v;
}

TEST(EditLevelSetsExample, RemovedToothLeavesAnEmptySocketAndTheRestUnchanged) {
    const fs::path dir = test::scratchDir("edit-example");
    const auto run = [&](const std::string& args, const std::string& log) {
        const test::CliResult r = test::runJawmesh(args, dir / log);
        EXPECT_EQ(r.exitCode, 0) << args << "\n" << r.output;
        return r.exitCode == 0;
    };
    const std::string caseDir = (dir / "case").string(), carved = (dir / "carved").string();
    ASSERT_TRUE(run("-q phantom " + caseDir + " --teeth 2", "phantom.log"));
    // 0.1 mm voxels keep it quick; the PDL is 2 voxels thick
    ASSERT_TRUE(run("-q carve " + caseDir + " -o " + carved + " --voxel 0.1", "carve.log"));
    const std::string levelsets = carved + "/mandible/levelsets", edited = (dir / "edited").string();
    const std::string edit = std::string(JAWMESH_REMOVE_TOOTH_EXAMPLE) + " " + levelsets + " 24 " + edited + " > " +
                             (dir / "edit.log").string() + " 2>&1";
    ASSERT_EQ(std::system(edit.c_str()), 0) << edit;
    EXPECT_FALSE(fs::exists(dir / "edited" / "tooth_24.vdb"));
    EXPECT_FALSE(fs::exists(dir / "edited" / "pdl_24.vdb"));
    EXPECT_TRUE(fs::exists(dir / "edited" / "tooth_25.vdb"));
    // the example refuses to overwrite, and names a tooth that is not there
    EXPECT_NE(std::system(edit.c_str()), 0);
    EXPECT_NE(std::system((std::string(JAWMESH_REMOVE_TOOTH_EXAMPLE) + " " + levelsets + " 31 " + (dir / "e31").string() +
                           " > /dev/null 2>&1")
                              .c_str()),
              0);
    EXPECT_FALSE(fs::exists(dir / "e31"));

    ASSERT_TRUE(run("-q run " + caseDir + " --from-vdb " + levelsets + " -o " + (dir / "whole").string(), "whole.log"));
    ASSERT_TRUE(run("-q run " + caseDir + " --from-vdb " + edited + " -o " + (dir / "out").string(), "out.log"));
    const TetMesh whole = readGmsh((dir / "whole" / "mandible" / "volumetric_meshes" / "mandible.msh").string());
    const TetMesh out = readGmsh((dir / "out" / "mandible" / "volumetric_meshes" / "mandible.msh").string());
    const auto before = volumeByLabel(whole), after = volumeByLabel(out);

    // every label but tooth 24 and PDL 24 stays, with its volume (the surfaces are simplified
    // independently, so not to the last digit)
    std::map<Label, double> expected = before;
    ASSERT_TRUE(expected.count(toothLabel(24)) && expected.count(pdlLabel(24)));
    expected.erase(toothLabel(24));
    expected.erase(pdlLabel(24));
    ASSERT_EQ(after.size(), expected.size());
    for (const auto& [L, v] : expected) {
        ASSERT_TRUE(after.count(L)) << labelName(L);
        EXPECT_NEAR(after.at(L), v, 0.01 * v) << labelName(L);
    }
    // the socket is empty: nothing took the place of tooth 24 and its PDL
    double total = 0, totalBefore = 0;
    for (const auto& [L, v] : after) total += v;
    for (const auto& [L, v] : before) totalBefore += v;
    EXPECT_NEAR(total, totalBefore - before.at(toothLabel(24)) - before.at(pdlLabel(24)), 0.01 * total);
}

}  // namespace
}  // namespace jawmesh
