// Implements levelset/JawLevelSetsIO.h; what it computes, its rules and its contract are documented there.
#include "levelset/JawLevelSetsIO.h"

#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/ToothAxes.h"
#include "levelset/Csg.h"
#include "levelset/LabelFieldIO.h"
#include "levelset/VdbFile.h"

#include <filesystem>
#include <fstream>
#include <regex>

namespace jawmesh {
namespace {

namespace fs = std::filesystem;

openvdb::FloatGrid::Ptr readLevelSet(const std::string& path) {
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(readGridFile(path));
    if (!grid) throw Error(path, "not a float grid (a level set)");
    bandHalfWidthMm(*grid);
    return grid;
}

}  // namespace

void writeJawLevelSets(const JawLevelSets& levelSets, Jaw jaw, const CarveOptions& carve, const std::string& dir) {
    fs::create_directories(dir);
    writeGridFile(levelSets.bone, dir + "/bone.vdb");
    for (const auto& [unn, grid] : levelSets.teeth) {
        const std::string kind = carve.implants.count(unn) ? "/implant_" : "/tooth_";
        writeGridFile(std::const_pointer_cast<openvdb::FloatGrid>(grid), dir + kind + std::to_string(unn) + ".vdb");
    }
    const nlohmann::json j = {{"jaw", jawName(jaw)}, {"options", toJson(carve)}};
    writeFileAtomically(dir + "/carve.json", [&](std::ostream& out) { out << j.dump(2) << '\n'; }, false);
    if (!carve.axes.empty()) writeToothAxes(carve.axes, dir + "/teeth_axes.json");
}

nlohmann::json readEditHistory(const std::string& dir) {
    const std::string path = dir + "/" + kEditHistoryFile;
    std::ifstream in(path);
    if (!in) return nlohmann::json::array();
    try {
        nlohmann::json history = nlohmann::json::parse(in);
        if (history.is_array()) return history;
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, std::string("not valid JSON: ") + e.what());
    }
    throw Error(path, "an edit history is a JSON array of edit records");
}

void writeEditHistory(const nlohmann::json& history, const std::string& dir) {
    writeFileAtomically(dir + "/" + kEditHistoryFile, [&](std::ostream& o) { o << history.dump(2) << '\n'; }, false);
}

void writeEditableFolder(const LabelField& field, const JawLevelSets& levelSets, Jaw jaw, const CarveOptions& carve,
                         const nlohmann::json& history, const std::string& dir) {
    writeLabelField(field, dir);
    writeJawLevelSets(levelSets, jaw, carve, dir + "/input");
    if (!history.empty()) writeEditHistory(history, dir);
}

StoredJawLevelSets readJawLevelSets(const std::string& dir) {
    const std::string carvePath = dir + "/carve.json";
    std::ifstream in(carvePath);
    if (!in) throw Error(carvePath, "missing: the folder holds no input level sets (write them with --write-levelsets)");
    StoredJawLevelSets s;
    try {
        const nlohmann::json j = nlohmann::json::parse(in);
        s.jaw = jawFromName(j.at("jaw").get<std::string>());
        s.carve = carveOptionsFromJson(j.at("options"), carvePath);
    } catch (const nlohmann::json::exception& e) {
        throw Error(carvePath, e.what());
    }
    if (fs::exists(dir + "/teeth_axes.json")) s.carve.axes = readToothAxes(dir + "/teeth_axes.json");
    s.levelSets.bone = readLevelSet(dir + "/bone.vdb");
    const std::regex tooth("(tooth|implant)_([0-9]+)\\.vdb");
    for (const auto& entry : fs::directory_iterator(dir)) {
        std::smatch m;
        const std::string name = entry.path().filename().string();
        if (!std::regex_match(name, m, tooth)) continue;
        const int unn = std::stoi(m[2]);
        if ((m[1] == "implant") != (s.carve.implants.count(unn) > 0))
            throw Error(entry.path().string(), "carve.json's \"implants\" and the grid files disagree on tooth " + std::to_string(unn));
        if (s.levelSets.teeth.count(unn)) throw Error(entry.path().string(), "a second grid for tooth " + std::to_string(unn));
        auto grid = readLevelSet(entry.path().string());
        requireSameTransform(*s.levelSets.bone, *grid, entry.path().c_str());
        s.levelSets.teeth[unn] = grid;
    }
    for (int unn : s.carve.implants)
        if (!s.levelSets.teeth.count(unn)) throw Error(carvePath, "implant_" + std::to_string(unn) + ".vdb is missing");
    return s;
}

}  // namespace jawmesh
