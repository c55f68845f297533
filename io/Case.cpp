// Implements io/Case.h; what it computes, its rules and its contract are documented there.
#include "io/Case.h"
#include "io/LabelVolume.h"

#include "io/Error.h"
#include "io/MeshIO.h"
#include "io/ParallelInOrder.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace jawmesh {
namespace fs = std::filesystem;

namespace {

std::vector<fs::path> sortedEntries(const fs::path& dir) {
    std::vector<fs::path> entries;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) entries.push_back(it->path());
    if (ec) throw Error(dir.string(), "cannot list folder: " + ec.message());
    std::sort(entries.begin(), entries.end());
    return entries;
}

bool isDir(const fs::path& p) {
    std::error_code ec;
    return fs::is_directory(p, ec);
}

bool isFile(const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec);
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string stemOf(const fs::path& p) { return p.stem().string(); }

bool isAllTeethObj(const fs::path& p) { return isFile(p) && lower(p.filename().string()) == "all_teeth.obj"; }

}  // namespace

std::string labelVolumeIn(const std::string& jawDir) {
    std::vector<std::string> found;
    for (const fs::path& p : sortedEntries(jawDir)) {
        const std::string file = lower(p.filename().string());
        if (isFile(p) && file.compare(0, 7, "labels.") == 0 && isLabelVolumePath(file)) found.push_back(p.string());
    }
    if (found.size() > 1) throw Error(jawDir, "several label volumes (" + found[0] + ", " + found[1] + "); keep one");
    return found.empty() ? "" : found[0];
}

std::map<int, std::string> toothFilesIn(const std::string& teethDir, Jaw jaw) {
    std::map<int, std::string> paths;
    for (const fs::path& p : sortedEntries(teethDir)) {
        if (!isFile(p) || !isSurfaceExtension(surfaceExtension(p.string())) || isAllTeethObj(p)) continue;
        const std::string stem = lower(stemOf(p));
        const std::string digits = stem.size() > 6 && stem.compare(0, 6, "tooth_") == 0 ? stem.substr(6) : "";
        if (digits.empty() || digits.size() > 3 || digits.find_first_not_of("0123456789") != std::string::npos)
            throw Error(p.string(), "cannot read a tooth number from this file name: expected tooth_<UNN>." +
                                        surfaceExtension(p.string()) + " (UNN 1..32) or all_teeth.obj");
        const int unn = std::stoi(digits);
        if (!isValidUnn(unn)) throw Error(p.string(), "tooth number " + std::to_string(unn) + " is outside 1..32");
        if (jawOfTooth(unn) != jaw)
            throw Error(p.string(), "tooth " + std::to_string(unn) + " belongs to the " + jawName(jawOfTooth(unn)) + " (" +
                                        (jaw == Jaw::Mandible ? "1..16" : "17..32") + "), not the " + jawName(jaw) + " (" +
                                        (jaw == Jaw::Mandible ? "17..32" : "1..16") + ")");
        const auto [it, inserted] = paths.emplace(unn, p.string());
        if (!inserted) throw Error(p.string(), "tooth " + std::to_string(unn) + " is given twice (also " + it->second + "); keep one");
    }
    return paths;
}

namespace {

/// A jaw given as a label volume: it may hold labels.json and an axes file, no surfaces.
JawCase discoverLabelJaw(const fs::path& jawDir, Jaw jaw, const std::string& volume) {
    const std::string name = jawName(jaw);
    for (const fs::path& surfaces : {jawDir / "bone", jawDir / "teeth", jawDir / "all_teeth.obj"})
        if (fs::exists(surfaces))
            throw Error(jawDir.string(), "both a label volume (" + volume + ") and surfaces (" + surfaces.string() +
                                             ") are given; keep one");
    JawCase jc;
    jc.jaw = jaw;
    jc.folder = jawDir.string();
    jc.labelVolumePath = volume;
    if (isFile(jawDir / "labels.json")) jc.labelsJsonPath = (jawDir / "labels.json").string();
    const fs::path axes = jawDir / ("teeth_axes_" + name + ".json");
    if (isFile(axes)) jc.axesPath = axes.string();
    return jc;
}

JawCase discoverJaw(const fs::path& jawDir, Jaw jaw) {
    const std::string name = jawName(jaw);
    const std::string volume = labelVolumeIn(jawDir.string());
    if (!volume.empty()) return discoverLabelJaw(jawDir, jaw, volume);
    JawCase jc;
    jc.jaw = jaw;
    jc.folder = jawDir.string();

    const fs::path boneDir = jawDir / "bone";
    std::vector<std::string> bones;
    if (isDir(boneDir))
        for (const fs::path& p : sortedEntries(boneDir))
            if (isFile(p) && lower(stemOf(p)) == name && isSurfaceExtension(surfaceExtension(p.string())))
                bones.push_back(p.string());
    if (bones.empty())
        throw Error(jawDir.string(), "no bone surface: expected bone/" + name + ".stl (or .obj, .ply, .off)");
    if (bones.size() > 1) throw Error(boneDir.string(), "several bone surfaces (" + bones[0] + ", " + bones[1] + "); keep one");
    jc.bonePath = bones[0];

    const fs::path teethDir = jawDir / "teeth";
    std::vector<std::string> allTeeth;
    if (isAllTeethObj(jawDir / "all_teeth.obj")) allTeeth.push_back((jawDir / "all_teeth.obj").string());
    if (isDir(teethDir)) {
        for (const fs::path& p : sortedEntries(teethDir))
            if (isAllTeethObj(p)) allTeeth.push_back(p.string());
        jc.toothPaths = toothFilesIn(teethDir.string(), jaw);
    }
    if (allTeeth.size() > 1) throw Error(allTeeth[1], "all_teeth.obj is given twice (also " + allTeeth[0] + "); keep one");
    if (!allTeeth.empty() && !jc.toothPaths.empty())
        throw Error(allTeeth[0], "both tooth_<UNN> files and all_teeth.obj are present; keep one");
    if (!allTeeth.empty()) {
        jc.teethFromAllTeethObj = true;
        jc.allTeethPath = allTeeth[0];
    }
    if (jc.toothPaths.empty() && !jc.teethFromAllTeethObj)
        throw Error(jawDir.string(), "no teeth: expected teeth/tooth_<UNN>.stl files (or .obj, .ply, .off) or teeth/all_teeth.obj");

    const fs::path axes = jawDir / ("teeth_axes_" + name + ".json");
    if (isFile(axes)) jc.axesPath = axes.string();
    return jc;
}

}  // namespace

CaseInfo discoverCase(const std::string& caseDir) {
    if (!fs::exists(caseDir)) throw Error(caseDir, "case folder does not exist");
    if (!isDir(caseDir)) throw Error(caseDir, "is not a folder (expected a case folder holding input/)");
    const fs::path input = fs::path(caseDir) / "input";
    if (!isDir(input)) throw Error(caseDir, "no input/ folder (expected input/<mandible|maxilla>/bone and teeth)");
    CaseInfo info;
    info.root = caseDir;
    for (Jaw jaw : {Jaw::Mandible, Jaw::Maxilla}) {
        const fs::path jawDir = input / jawName(jaw);
        if (isDir(jawDir)) info.jaws.push_back(discoverJaw(jawDir, jaw));
    }
    if (info.jaws.empty()) throw Error(input.string(), "no jaw: expected a mandible/ or maxilla/ folder");
    return info;
}

// ---------------------------------------------------------------------------------------------

JawSurfaces loadJaw(const JawCase& jc, const LoadOptions& options, Progress& progress) {
    if (!jc.labelVolumePath.empty())
        throw Error(jc.labelVolumePath, "a label volume is read by loadJawInput (levelset/JawInput.h), not as surfaces");
    requireValidScale(options, jc.bonePath);
    JawSurfaces out;
    out.jaw = jc.jaw;

    std::vector<std::string> paths{jc.bonePath};
    std::vector<int> unns{0};
    if (jc.teethFromAllTeethObj) {
        paths.push_back(jc.allTeethPath);
        unns.push_back(0);
    }
    for (const auto& [unn, path] : jc.toothPaths) {
        paths.push_back(path);
        unns.push_back(unn);
    }
    std::vector<SurfaceMesh> meshes(paths.size());
    {
        ProgressStage stage(progress, "read " + jawName(jc.jaw) + " surfaces");
        // the first failing file in a fixed order, whatever the threads
        parallelForFirstErrorInOrder(paths.size(), progress, [&](std::size_t i) { meshes[i] = readSurface(paths[i]); });
    }
    out.bone = std::move(meshes[0]);
    if (!jc.axesPath.empty()) out.axes = readToothAxes(jc.axesPath);

    if (options.scale > 0) {
        auto scale = [&](SurfaceMesh& m) {
            for (Vec3& v : m.vertices) v *= options.scale;
        };
        scale(out.bone);
        for (std::size_t i = 1; i < meshes.size(); ++i) scale(meshes[i]);
        for (auto& [unn, a] : out.axes) a.crownCentre *= options.scale;
        out.notes.push_back("coordinates multiplied by " + std::to_string(options.scale));
    } else {
        BBox box = boundingBox(out.bone);
        for (std::size_t i = 1; i < meshes.size(); ++i) box.extend(boundingBox(meshes[i]));
        const double diagonal = box.size().norm();
        if (diagonal < 1.0 || diagonal > 1000.0) {
            std::ostringstream msg;
            msg << "the " << jawName(jc.jaw) << " case's bounding box diagonal is " << diagonal << " but should be in "
                << "millimetres (between 1 and 1000): the coordinates look like "
                << (diagonal < 1.0 ? "metres (pass scale 1000)" : "micrometres or another unit (pass an explicit scale)")
                << "; an explicit scale multiplies every coordinate and skips this check";
            throw Error(jc.bonePath, msg.str());
        }
    }

    if (jc.teethFromAllTeethObj) {
        std::vector<std::string> notes;
        try {
            out.teeth = numberTeethAlongArch(meshes[1], jc.jaw, out.bone, &notes);
        } catch (const Error& e) {
            throw Error(jc.allTeethPath, e.reason());
        }
        for (const auto& [unn, tooth] : out.teeth)
            if (jawOfTooth(unn) != jc.jaw) throw Error(jc.allTeethPath, "numbering gave tooth " + std::to_string(unn) + " of the other jaw");
        out.notes.insert(out.notes.end(), notes.begin(), notes.end());
    } else {
        for (std::size_t i = 1; i < meshes.size(); ++i) out.teeth.emplace(unns[i], std::move(meshes[i]));
    }
    for (const auto& [unn, a] : out.axes)
        if (!out.teeth.count(unn))
            out.notes.push_back(jc.axesPath + ": axes of tooth " + std::to_string(unn) + " ignored (no such tooth)");
    return out;
}

std::string boneSource(const JawCase& jawCase) {
    return jawCase.labelVolumePath.empty() ? jawCase.bonePath : jawCase.labelVolumePath;
}

void requireValidScale(const LoadOptions& options, const std::string& file) {
    if (!(options.scale >= 0) || !std::isfinite(options.scale))
        throw Error(file, "scale must be a positive number (or 0 for automatic), not " + std::to_string(options.scale));
}

std::string toothSource(const JawCase& jawCase, int unn) {
    const auto file = jawCase.toothPaths.find(unn);
    if (file != jawCase.toothPaths.end()) return file->second;
    const std::string& source = jawCase.labelVolumePath.empty() ? jawCase.allTeethPath : jawCase.labelVolumePath;
    return source + " (tooth " + std::to_string(unn) + ")";
}

}  // namespace jawmesh
