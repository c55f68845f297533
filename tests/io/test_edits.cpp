// Edit files (io/Edits.h): the issue's example reads as written and round-trips through run.json's
// form; every malformed entry is refused with the file and the entry named.
#include "io/Edits.h"
#include "io/Error.h"

#include <gtest/gtest.h>

#include <fstream>
#include <filesystem>

using namespace jawmesh;

namespace {

std::string refusal(const std::string& text) {
    try {
        parseEdits(nlohmann::json::parse(text), "e.json");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(EditFile, ReadsTheIssuesExampleAndRoundTrips) {
    const auto path = std::filesystem::temp_directory_path() / "jawmesh_edits_test.json";
    std::ofstream(path) << R"({"edits": [
        {"op": "bone_loss", "teeth": [26, 23, 24, 25], "depth_mm": 2.0},
        {"op": "extract", "tooth": 30, "socket": "healed"},
        {"op": "pdl_thickness", "tooth": 24, "thickness_mm": 0.3},
        {"op": "pdl_thickness", "tooth": 19, "profile_mm": {"cervical": 0.3, "mid_root": 0.2, "apical": 0.25}},
        {"op": "extract", "tooth": 31},
        {"op": "bone_loss", "tooth": 27, "side": "distal", "depth_mm": 3.0, "width_mm": 1.5},
        {"op": "implant", "tooth": 18, "diameter_mm": 4.1, "length_mm": 10.0},
        {"op": "implant", "tooth": 20, "diameter_mm": 3.5, "length_mm": 8.0, "body": "screw", "platform_depth_mm": 0.5,
         "thread_pitch_mm": 0.6, "crown": "none"}
    ]})";
    const EditList list = readEditFile(path.string());
    std::filesystem::remove(path);
    ASSERT_EQ(list.edits.size(), 8u);
    const auto& implant = std::get<ImplantEdit>(list.edits[6]);
    EXPECT_EQ(implant.diameterMm, 4.1);
    EXPECT_EQ(implant.lengthMm, 10.0);
    EXPECT_EQ(implant.body, ImplantEdit::Body::Cylinder);
    EXPECT_TRUE(implant.crown);
    const auto& screw = std::get<ImplantEdit>(list.edits[7]);
    EXPECT_EQ(screw.body, ImplantEdit::Body::Screw);
    EXPECT_EQ(screw.threadPitchMm, 0.6);
    EXPECT_EQ(screw.threadDepthMm, 0.3);
    EXPECT_EQ(screw.platformDepthMm, 0.5);
    EXPECT_FALSE(screw.crown);
    EXPECT_EQ(implantedTeeth(list), (std::vector<int>{18, 20}));
    const auto& defect = std::get<AngularDefectEdit>(list.edits[5]);
    EXPECT_EQ(defect.side, AngularDefectEdit::Side::Distal);
    EXPECT_EQ(defect.widthMm, 1.5);
    const auto& loss = std::get<BoneLossEdit>(list.edits[0]);
    EXPECT_EQ(loss.teeth, (std::vector<int>{23, 24, 25, 26}));
    EXPECT_EQ(loss.depthMm, 2.0);
    EXPECT_TRUE(std::get<ExtractEdit>(list.edits[1]).healed);
    EXPECT_FALSE(std::get<ExtractEdit>(list.edits[4]).healed);
    EXPECT_EQ(std::get<PdlThicknessEdit>(list.edits[2]).apicalMm, 0.3);
    EXPECT_EQ(std::get<PdlThicknessEdit>(list.edits[3]).cervicalMm, 0.3);
    EXPECT_EQ(extractedTeeth(list), (std::vector<int>{30, 31}));
    const nlohmann::json recorded = toJson(list);
    EXPECT_EQ(toJson(parseEdits({{"edits", recorded.at("edits")}}, "again")).at("edits"), recorded.at("edits"));
    EXPECT_NO_THROW(requireEditsFit(list, {18, 19, 20, 23, 24, 25, 26, 27, 30, 31}));
    try {
        requireEditsFit(list, {18, 19, 20, 23, 24, 25, 27, 30, 31});
        FAIL() << "tooth 26 is missing";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("edits[0]: tooth 26 is not in this jaw"), std::string::npos) << e.what();
    }
}

TEST(EditFile, RefusesMalformedEntriesNamingFileAndEntry) {
    EXPECT_NE(refusal(R"({"edit": []})").find("e.json"), std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"tooth": 3}]})").find("e.json: edits[0]"), std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "implode", "tooth": 3}]})").find("edits[0] (implode): unknown op"), std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "extract", "tooth": 33}]})").find("UNN from 1 to 32"), std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "extract", "tooth": 3, "socket": "filled"}]})").find("'socket'"), std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "bone_loss", "teeth": [3], "depth_mm": -1}]})").find("'depth_mm' is -1"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "bone_loss", "teeth": [3], "depth": 2}]})").find("'depth_mm' is missing"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "bone_loss", "teeth": [3, 3], "depth_mm": 2}]})").find("twice"), std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "bone_loss", "teeth": [3], "depth_mm": 2, "width": 1}]})").find("unknown key 'width'"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "bone_loss", "tooth": 3, "side": "up", "depth_mm": 2, "width_mm": 1}]})").find("'side' must be"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "bone_loss", "tooth": 3, "side": "buccal", "depth_mm": 2}]})").find("'width_mm' is missing"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "pdl_thickness", "tooth": 3}]})").find("either 'thickness_mm' or 'profile_mm'"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "pdl_thickness", "tooth": 3, "thickness_mm": 0}]})").find("'thickness_mm' is 0"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "extract", "tooth": 3}, {"op": "pdl_thickness", "tooth": 3, "thickness_mm": 0.3}]})")
                  .find("edits[1] (pdl_thickness): tooth 3 was extracted by an earlier edit"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "implant", "tooth": 19, "diameter_mm": -4.1, "length_mm": 10}]})").find("'diameter_mm' is -4.1"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "implant", "tooth": 19, "diameter_mm": 4.1}]})").find("'length_mm' is missing"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "implant", "tooth": 19, "diameter_mm": 4.1, "length_mm": 10, "body": "blade"}]})").find("'body'"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "implant", "tooth": 19, "diameter_mm": 4.1, "length_mm": 10, "body": "screw",
                                     "thread_depth_mm": 1.0}]})").find("'thread_depth_mm' is 1"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"edits": [{"op": "implant", "tooth": 19, "diameter_mm": 4.1, "length_mm": 10},
                                    {"op": "pdl_thickness", "tooth": 19, "thickness_mm": 0.3}]})")
                  .find("edits[1] (pdl_thickness): tooth 19 was replaced by an implant by an earlier edit"),
              std::string::npos);
    try {
        readEditFile("/nonexistent/edits.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/edits.json"), std::string::npos);
    }
}
