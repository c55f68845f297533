// Run options (cli/RunOptions.h): every key run.json records is accepted back by --config and
// lands in the option it names; out-of-range values and unknown keys are refused with the key.
#include "cli/RunOptions.h"
#include "io/Error.h"

#include <gtest/gtest.h>

#include <string>

using namespace jawmesh;

TEST(RunOptions, RecordedKeysReadBackToTheSameOptions) {
    RunOptions changed = defaultRunOptions();
    changed.simplify.pdlErrorMm = 0.031;
    changed.simplify.pdlMaxEdgeMm = 0.77;
    changed.simplify.capMaxEdgeMm = 0.07;
    changed.carve.boneShiftMaxMm = 0.15;
    changed.carve.profile = PdlProfile{0.25, 0.2, 0.15};  // cervical, mid-root, apical mm
    changed.carve.apexTaperMm = 1.5;
    changed.tet.boneEdgeMm = 2.5;
    const nlohmann::json recorded = runOptionsToJson(changed);
    RunOptions back = defaultRunOptions();
    applyRunConfigText(recorded.dump(), "run.json", back);
    EXPECT_EQ(runOptionsToJson(back), recorded);
    EXPECT_DOUBLE_EQ(back.simplify.pdlErrorMm, 0.031);
    EXPECT_DOUBLE_EQ(back.simplify.pdlMaxEdgeMm, 0.77);
    EXPECT_DOUBLE_EQ(back.simplify.capMaxEdgeMm, 0.07);
    EXPECT_DOUBLE_EQ(back.carve.boneShiftMaxMm, 0.15);
    EXPECT_DOUBLE_EQ(back.carve.apexTaperMm, 1.5);
    EXPECT_DOUBLE_EQ(back.tet.boneEdgeMm, 2.5);
    ASSERT_TRUE(back.carve.profile.has_value());
    EXPECT_DOUBLE_EQ(back.carve.profile->cervical, 0.25);
    EXPECT_DOUBLE_EQ(back.carve.profile->apical, 0.15);
    // Every number the record holds is one the config can set.
    for (const auto& [key, value] : recorded.items()) {
        if (value.is_number()) {
            EXPECT_NO_THROW(applyRunConfigText("{\"" + key + "\": " + value.dump() + "}", "k.json", back)) << key;
        }
    }
}

TEST(RunOptions, RefusesOutOfRangeValuesNamingTheKey) {
    for (const std::string key : {"surface_pdl_max_edge_mm", "surface_cap_max_edge_mm", "surface_pdl_error_mm",
                                  "bone_shift_max_mm", "apex_taper_mm", "voxel_mm"}) {
        RunOptions o = defaultRunOptions();
        const RunOptions before = o;
        try {
            applyRunConfigText("{\"" + key + "\": -1}", "bad.json", o);
            ADD_FAILURE() << key << " = -1 was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("'" + key + "'"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
        }
        EXPECT_EQ(runOptionsToJson(o), runOptionsToJson(before)) << "options changed by a refused file";
    }
    RunOptions o = defaultRunOptions();
    EXPECT_THROW(applyRunConfigText(R"({"surface_pdl_max_edge": 0.5})", "typo.json", o), Error);
    // the adaptive extraction's levels: a whole number from 0 (the fine extraction) to 5
    for (const char* bad : {R"({"surface_adaptive_levels": 2.5})", R"({"surface_adaptive_levels": 6})",
                            R"({"surface_adaptive_levels": -1})"}) {
        try {
            applyRunConfigText(bad, "levels.json", o);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("'surface_adaptive_levels'"), std::string::npos) << e.what();
        }
    }
    applyRunConfigText(R"({"surface_adaptive_levels": 0})", "fine.json", o);
    EXPECT_EQ(o.extract.adaptive.maxLevel, 0);
    EXPECT_EQ(runOptionsToJson(o).at("surface_adaptive_levels"), 0);
}
