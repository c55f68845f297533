// Tooth axes JSON: round trip and malformed files.
#include "io/ToothAxes.h"
#include "support/TestData.h"
#include "io/IoTestUtil.h"

namespace jawmesh::test {
namespace {

TEST(ToothAxes, RoundTripKeepsUnitAxes) {
    std::map<int, ToothAxes> axes;
    ToothAxes a;
    a.crownCentre = Vec3(29.07, 47.11, 70.57);
    a.mesialDistal = Vec3(1, 2, 2).normalized();
    a.labial = Vec3(-2, 1, 0).normalized();
    a.occlusal = a.mesialDistal.cross(a.labial);
    axes[1] = a;
    axes[24] = ToothAxes{};
    const auto path = (scratchDir("io-axes") / "teeth_axes_maxilla.json").string();
    writeToothAxes(axes, path);
    const auto back = readToothAxes(path);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_LT((back.at(1).crownCentre - a.crownCentre).norm(), 1e-12);
    EXPECT_LT((back.at(1).mesialDistal - a.mesialDistal).norm(), 1e-12);
    EXPECT_LT((back.at(1).labial - a.labial).norm(), 1e-12);
    EXPECT_LT((back.at(1).occlusal - a.occlusal).norm(), 1e-12);
    EXPECT_LT((back.at(24).occlusal - Vec3::UnitZ()).norm(), 1e-12);
}

TEST(ToothAxes, EndPointsBecomeUnitVectors) {
    const auto path = scratchDir("io-axes-unit") / "a.json";
    writeBytes(path, R"({"7": {"c": [1, 1, 1], "x": [3, 1, 1], "y": [1, 1.5, 1], "z": [1, 1, -9]}})");
    const auto axes = readToothAxes(path.string());
    EXPECT_LT((axes.at(7).mesialDistal - Vec3::UnitX()).norm(), 1e-12);
    EXPECT_LT((axes.at(7).labial - Vec3::UnitY()).norm(), 1e-12);
    EXPECT_LT((axes.at(7).occlusal + Vec3::UnitZ()).norm(), 1e-12);
}

TEST(ToothAxes, MalformedFilesNameTheFile) {
    const auto dir = scratchDir("io-axes-bad");
    const std::pair<const char*, const char*> cases[] = {
        {"{", "invalid JSON"},
        {"[1, 2]", "JSON object"},
        {R"({"abc": {}})", "tooth number"},
        {R"({"33": {}})", "tooth number"},
        {R"({"5": 3})", "expected an object"},
        {R"({"5": {"x": [0,0,0], "y": [0,0,0], "z": [0,0,0]}})", "missing \"c\""},
        {R"({"5": {"c": [0,0], "x": [1,0,0], "y": [0,1,0], "z": [0,0,1]}})", "3 numbers"},
        {R"({"5": {"c": [0,0,"a"], "x": [1,0,0], "y": [0,1,0], "z": [0,0,1]}})", "3 numbers"},
        {R"({"5": {"c": [0,0,0], "x": [0,0,0], "y": [0,1,0], "z": [0,0,1]}})", "zero length"},
        {R"({"5": {"c": [0,0,0], "x": [1,0,0], "y": [0,1,0], "z": [0,0,1]}, "05": {"c": [0,0,0], "x": [1,0,0], "y": [0,1,0], "z": [0,0,1]}})", "twice"},
    };
    int i = 0;
    for (const auto& [text, fragment] : cases) {
        const std::string path = (dir / ("bad" + std::to_string(i++) + ".json")).string();
        writeBytes(path, text);
        SCOPED_TRACE(text);
        expectErrorNaming([&] { readToothAxes(path); }, path, fragment);
    }
    expectErrorNaming([&] { readToothAxes((dir / "missing.json").string()); }, "missing.json", "cannot open");
}

}  // namespace
}  // namespace jawmesh::test
