// Implements cli/EvalReport.h; what it computes, its rules and its contract are documented there.
#include "cli/EvalReport.h"

#include "filters/CrossSection.h"
#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/PngWriter.h"
#include "io/ReportHtml.h"
#include "io/ResourceUsage.h"
#include "levelset/JawInput.h"
#include "levelset/UnionBoundary.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <set>

namespace fs = std::filesystem;

namespace jawmesh {
namespace {

constexpr int kToothSectionPixels = 520;  // image height of a tooth section
constexpr int kArchSectionPixels = 1100;  // longer side of the arch section

/// Label colours, element edges darkened so the grading shows.
RgbImage colourSection(const SectionRaster& r) {
    RgbImage img;
    img.width = r.width;
    img.height = r.height;
    img.rgb.resize(3 * r.label.size());
    for (std::size_t i = 0; i < r.label.size(); ++i) {
        auto c = labelColour(r.label[i]);
        if (r.edge[i] && r.label[i] != kOutsideLabel)
            for (auto& v : c) v = static_cast<std::uint8_t>(v * 0.62);
        std::copy(c.begin(), c.end(), img.rgb.begin() + static_cast<std::ptrdiff_t>(3 * i));
    }
    return img;
}

struct Section {
    std::string name, caption;
    SectionPlane plane;
    double pixelMm;
    std::string png;
};

/// A jaw's input as the evaluation compares with it: a tooth given as overlapping shells is its
/// shells' union, not its pulp.
JawSurfaces evalInput(const JawCase& jawCase, const LoadOptions& load, Progress& progress) {
    return toothUnionBoundaries(loadJawInput(jawCase, load, progress));
}

}  // namespace

nlohmann::json writeEvalReport(const TetMesh& mesh, const JawSurfaces* input, const EvalOptions& options,
                               const std::string& dir, const std::string& title, Progress& progress) {
    nlohmann::json report = evaluateMesh(mesh, input, options, progress);
    std::vector<Section> sections;
    if (report.contains("regions")) {
        ProgressStage stage(progress, "eval: cross-sections");
        std::set<int> teeth;
        for (Label l : mesh.labels)
            if (labelKind(l) == LabelKind::Tooth) teeth.insert(labelUnn(l));
        if (auto arch = archSectionPlane(mesh)) {
            const double px = std::max(arch->widthMm, arch->heightMm) / kArchSectionPixels;
            sections.push_back({"arch", "", *arch, px, {}});
        }
        const std::vector<int> unns(teeth.begin(), teeth.end());
        std::vector<std::optional<SectionPlane>> planes(unns.size());
        tbb::parallel_for(std::size_t{0}, unns.size(), [&](std::size_t i) { planes[i] = toothSectionPlane(mesh, unns[i]); });
        for (std::size_t i = 0; i < unns.size(); ++i)
            if (const auto& p = planes[i])
                sections.push_back({"tooth_" + std::to_string(unns[i]), "", *p, p->heightMm / kToothSectionPixels, {}});
        tbb::parallel_for(std::size_t{0}, sections.size(), [&](std::size_t i) {
            Section& s = sections[i];
            s.png = encodePng(colourSection(rasterizeSection(mesh, s.plane, s.pixelMm)));
        });
        for (Section& s : sections) {
            char buf[200];
            std::snprintf(buf, sizeof buf, "%.1f x %.1f mm, %.3f mm per pixel; centre (%.2f, %.2f, %.2f), normal (%.3f, %.3f, %.3f)",
                          s.plane.widthMm, s.plane.heightMm, s.pixelMm, s.plane.centreMm.x(), s.plane.centreMm.y(),
                          s.plane.centreMm.z(), s.plane.right.cross(s.plane.up).x(), s.plane.right.cross(s.plane.up).y(),
                          s.plane.right.cross(s.plane.up).z());
            s.caption = (s.name == "arch" ? std::string("Arch at the height of the PDLs: ")
                                          : s.name + " along its long axis, buccolingual (occlusal up): ") + buf;
            report["sections"].push_back({{"name", s.name}, {"file", "sections/" + s.name + ".png"}, {"caption", s.caption}});
        }
    }
    std::vector<ReportPicture> pictures;
    for (const Section& s : sections) {
        const std::string path = (fs::path(dir) / "sections" / (s.name + ".png")).string();
        writeFileAtomically(path, [&](std::ostream& out) { out.write(s.png.data(), static_cast<std::streamsize>(s.png.size())); });
        pictures.push_back({"section-" + s.name, s.caption, s.png});
    }
    writeFileAtomically((fs::path(dir) / "report.json").string(), [&](std::ostream& out) { out << report.dump(2) << '\n'; }, false);
    const std::string html = reportHtml(report, pictures, title);
    writeFileAtomically((fs::path(dir) / "report.html").string(), [&](std::ostream& out) { out << html; }, false);
    return report;
}

JawSurfaces loadEvalInput(const std::string& path, Jaw jaw, const LoadOptions& load, Progress& progress) {
    const fs::path p = fs::path(path).lexically_normal();
    const fs::path folder = p.filename().empty() ? p.parent_path() : p;
    fs::path caseRoot = folder;
    const bool labelVolume = fs::is_directory(folder) && !labelVolumeIn(folder.string()).empty();
    if (fs::is_directory(folder / "bone") || fs::is_directory(folder / "teeth") || labelVolume) {  // <case>/input/<jaw>
        jaw = jawFromName(folder.filename().string());
        caseRoot = folder.parent_path().parent_path();
        if (caseRoot.empty()) caseRoot = ".";
    } else if (!fs::is_directory(folder / "input")) {
        throw Error(path, "not an input folder: expected <case>/input/<jaw> (with bone/ and teeth/) or a case folder with input/");
    }
    const CaseInfo info = discoverCase(caseRoot.string());
    for (const JawCase& jc : info.jaws)
        if (jc.jaw == jaw) return evalInput(jc, load, progress);
    throw Error(path, "the case has no " + jawName(jaw) + " input");
}

namespace {
/// "<case folder> <jaw>": the end-of-run report names its input, not the folder it is written to
/// (a batch writes into a temporary folder and renames it, so outputs must not depend on it).
std::string caseTitle(const JawCase& jawCase) {
    const fs::path folder = fs::absolute(jawCase.folder).lexically_normal();  // <case>/input/<jaw>
    return folder.parent_path().parent_path().filename().string() + " " + jawName(jawCase.jaw);
}
}  // namespace

void judgeAgainstEdits(const nlohmann::json& history, EvalOptions& options, std::vector<int>& removedTeeth) {
    options.edits = history;
    for (const auto& record : history)
        for (const auto& e : record.at("applied")) {
            const std::string op = e.at("op");
            if (op == "extract" || op == "implant") {  // no input surface of that tooth is left
                const int unn = e.at("tooth").get<int>();
                removedTeeth.push_back(unn);
                options.toothPdlTargetMm.erase(unn);
            } else if (op == "pdl_thickness") {
                const int unn = e.at("tooth").get<int>();
                const auto& p = e.at("profile_mm");
                const double mid = p.at("mid_root").get<double>();
                options.toothPdlTargetMm[unn] = p.at("cervical") == mid && p.at("apical") == mid ? mid : 0.0;
            }
        }
}

nlohmann::json runReport(const TetMesh& mesh, const JawCase& jawCase, const LoadOptions& load, JawSurfaces* loaded,
                         const EvalOptions& options, const std::vector<int>& removedTeeth, const std::string& outJawDir,
                         Progress& progress) {
    const auto start = std::chrono::steady_clock::now();
    try {
        JawSurfaces input = loaded ? toothUnionBoundaries(std::move(*loaded)) : evalInput(jawCase, load, progress);
        for (int unn : removedTeeth) input.teeth.erase(unn);
        const nlohmann::json report =
            writeEvalReport(mesh, &input, options, outJawDir + "/report", caseTitle(jawCase), progress);
        return {{"status", report["verdict"]["status"]},
                {"line", report["verdict"]["line"]},
                {"report", "report/report.html"},
                {"seconds", secondsSince(start)}};
    } catch (const Error& e) {
        return {{"error", e.what()}};
    }
}

}  // namespace jawmesh
