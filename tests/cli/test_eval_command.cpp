// `jawmesh eval` end to end on the synthetic jaw written as files: report.json and a self-contained
// report.html whose tables and pictures exist, decode and are not blank; the page rendered by
// headless Chromium shows them; bad input stops with a message naming the file.
#include "io/GmshWriter.h"
#include "io/MeshIO.h"
#include "support/PngDecode.h"
#include "support/SyntheticJaw.h"
#include "support/TestData.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

namespace fs = std::filesystem;
using namespace jawmesh;
using namespace jawmesh::test;

namespace {

struct CommandResult {
    int exitCode;
    std::string err;
};

CommandResult runWithStderr(const std::string& args, const fs::path& dir) {
    const fs::path errFile = dir / "stderr.txt";
    const int status = std::system((std::string(JAWMESH_BINARY) + " " + args + " 2> " + errFile.string() + " > /dev/null").c_str());
    return {WEXITSTATUS(status), test::readText(errFile.string())};
}

/// The synthetic jaw as a run output (.msh) and its input case, in a fresh folder.
fs::path writeSyntheticCase(const std::string& name) {
    const fs::path dir = processScratchDir(name);
    writeGmsh(syntheticJawMesh(), (dir / "mandible.msh").string());
    const JawSurfaces in = syntheticJawInput();
    writeSurface(in.bone, (dir / "case/input/mandible/bone/mandible.stl").string());
    for (const auto& [unn, s] : in.teeth) writeSurface(s, (dir / ("case/input/mandible/teeth/tooth_" + std::to_string(unn) + ".stl")).string());
    return dir;
}

/// Pixels of a colour (within +-6 per channel).
std::size_t countColour(const DecodedPng& img, std::array<int, 3> c) {
    std::size_t n = 0;
    for (const auto& p : img.rgb)
        n += std::abs(p[0] - c[0]) <= 6 && std::abs(p[1] - c[1]) <= 6 && std::abs(p[2] - c[2]) <= 6;
    return n;
}

class EvalCommand : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new fs::path(writeSyntheticCase("eval-command"));
        const CommandResult r = runWithStderr("eval " + (*dir_ / "mandible.msh").string() + " --input " + (*dir_ / "case/input/mandible").string() +
                                  " -o " + (*dir_ / "report").string(),
                              *dir_);
        exitCode_ = r.exitCode;
        err_ = new std::string(r.err);
    }
    static void TearDownTestSuite() {
        delete dir_;
        delete err_;
    }
    static fs::path* dir_;
    static std::string* err_;
    static int exitCode_;
};
fs::path* EvalCommand::dir_ = nullptr;
std::string* EvalCommand::err_ = nullptr;
int EvalCommand::exitCode_ = -1;

}  // namespace

TEST_F(EvalCommand, WritesReportJsonAndSelfContainedHtml) {
    ASSERT_EQ(exitCode_, 0) << *err_;
    EXPECT_NE(err_->find("WARN"), std::string::npos) << *err_;  // the verdict line is printed
    std::ifstream in(*dir_ / "report/report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_EQ(report["schema"], "jawmesh-eval/1");
    EXPECT_EQ(report["distance"]["domains"].size(), 3u);
    EXPECT_EQ(report["sections"].size(), 3u);  // arch + one per tooth

    const std::string html = test::readText((*dir_ / "report/report.html").string());
    for (const char* id : {"id=\"verdict\"", "id=\"sizes\"", "id=\"regions\"", "id=\"hausdorff\"", "id=\"pdl\"", "id=\"hist-radius_ratio\"",
                           "id=\"hist-volume_edge_ratio\"", "id=\"hist-radius_edge_ratio\"", "id=\"hist-min_dihedral_deg\"",
                           "id=\"hist-pdl-thickness\"", "id=\"section-arch\"", "id=\"section-tooth_24\"", "id=\"section-tooth_25\""})
        EXPECT_NE(html.find(id), std::string::npos) << id;
    EXPECT_EQ(html.find("src=\"sections/"), std::string::npos);  // pictures embedded, nothing to fetch
    // Every embedded picture decodes and shows bone, tooth and PDL colours.
    // (std::regex would recurse per character of a long base64 run and overflow the stack.)
    const std::string marker = "data:image/png;base64,";
    int pictures = 0;
    for (std::size_t at = html.find(marker); at != std::string::npos; at = html.find(marker, at + 1), ++pictures) {
        const std::size_t begin = at + marker.size(), end = html.find('"', begin);
        ASSERT_NE(end, std::string::npos);
        std::string bytes;
        static const std::string table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::uint32_t acc = 0;
        int bits = 0;
        for (std::size_t i = begin; i < end && html[i] != '='; ++i) {
            acc = (acc << 6) | static_cast<std::uint32_t>(table.find(html[i]));
            bits += 6;
            if (bits >= 8) {
                bits -= 8;
                bytes.push_back(static_cast<char>((acc >> bits) & 0xff));
            }
        }
        const DecodedPng img = decodePng(bytes);
        EXPECT_GT(img.width, 100);
        EXPECT_GT(countColour(img, {214, 48, 48}), 100u) << "PDL visible in picture " << pictures;
        EXPECT_GT(countColour(img, {222, 196, 140}), 100u) << "bone visible in picture " << pictures;
        EXPECT_EQ(bytes, test::readText((*dir_ / "report" / report["sections"][static_cast<std::size_t>(pictures)]["file"].get<std::string>()).string()));
    }
    EXPECT_EQ(pictures, 3);
}

TEST_F(EvalCommand, ChromiumRendersTablesAndPictures) {
    ASSERT_EQ(exitCode_, 0) << *err_;
    std::string chromium;
    for (const char* name : {"chromium", "chromium-browser", "google-chrome"})
        if (std::system((std::string("command -v ") + name + " > /dev/null 2>&1").c_str()) == 0) chromium = name;
    if (chromium.empty()) GTEST_SKIP() << "no chromium installed (Debian package `chromium`; quickstart.sh installs it)";
    const fs::path shot = *dir_ / "screenshot.png";
    const std::string cmd = chromium + " --headless --no-sandbox --disable-gpu --hide-scrollbars --screenshot=" + shot.string() +
                            " --window-size=1400,4000 file://" + fs::absolute(*dir_ / "report/report.html").string() + " > " +
                            (*dir_ / "chromium.log").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << test::readText((*dir_ / "chromium.log").string());
    const DecodedPng img = decodePng(test::readText(shot.string()));
    ASSERT_EQ(img.width, 1400);
    std::size_t nonWhite = 0;
    for (const auto& p : img.rgb) nonWhite += p[0] < 240 || p[1] < 240 || p[2] < 240;
    EXPECT_GT(nonWhite, img.rgb.size() / 50) << "page looks blank";
    EXPECT_GT(countColour(img, {255, 241, 204}), 5000u) << "verdict box (warn) not visible";
    EXPECT_GT(countColour(img, {238, 238, 238}), 2000u) << "table headers not visible";
    EXPECT_GT(countColour(img, {214, 48, 48}), 2000u) << "cross-section pictures (PDL red) not visible";
    EXPECT_GT(countColour(img, {222, 196, 140}), 20000u) << "cross-section pictures (bone) not visible";
}

TEST(EvalCommandErrors, BadInputNamesTheFileAndFails) {
    const fs::path dir = writeSyntheticCase("eval-command-errors");
    {
        std::ofstream(dir / "broken.msh") << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 5 1 5\n";
        const CommandResult r = runWithStderr("eval " + (dir / "broken.msh").string() + " -o " + (dir / "out").string(), dir);
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_NE(r.err.find("broken.msh"), std::string::npos) << r.err;
    }
    {
        std::ofstream(dir / "mesh.vtu") << "<VTKFile/>";
        const CommandResult r = runWithStderr("eval " + (dir / "mesh.vtu").string() + " -o " + (dir / "out").string(), dir);
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_NE(r.err.find("mesh.vtu"), std::string::npos) << r.err;
    }
    {
        const CommandResult r = runWithStderr("eval " + (dir / "mandible.msh").string() + " --input " + dir.string() + " -o " + (dir / "out").string(), dir);
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_NE(r.err.find("not an input folder"), std::string::npos) << r.err;
    }
    {
        // Another jaw's input: the surfaces are somewhere else entirely.
        JawSurfaces other = syntheticJawInput();
        for (SurfaceMesh* s : {&other.bone, &other.teeth.at(24), &other.teeth.at(25)})
            for (Vec3& v : s->vertices) v += Vec3(60, 0, 0);
        writeSurface(other.bone, (dir / "other/input/mandible/bone/mandible.stl").string());
        for (int unn : {24, 25})
            writeSurface(other.teeth.at(unn), (dir / ("other/input/mandible/teeth/tooth_" + std::to_string(unn) + ".stl")).string());
        const CommandResult r = runWithStderr("eval " + (dir / "mandible.msh").string() + " --input " + (dir / "other").string() + " -o " +
                                               (dir / "out").string(),
                                           dir);
        EXPECT_EQ(r.exitCode, 1);
        EXPECT_NE(r.err.find("do not match the mesh"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "out/report.json"));
    // Without --input the report still has quality and PDL thickness, and no distances.
    const CommandResult ok = runWithStderr("--quiet eval " + (dir / "mandible.msh").string() + " -o " + (dir / "bare").string(), dir);
    ASSERT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_TRUE(ok.err.empty()) << ok.err;  // --quiet
    std::ifstream in(dir / "bare/report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_TRUE(report["distance"].is_null());
    EXPECT_EQ(report["pdl_thickness"]["teeth"].size(), 2u);
}
