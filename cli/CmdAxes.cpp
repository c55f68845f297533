// jawmesh axes <case>: tooth axes of a case, from its teeth_axes JSON when present, else computed
// from the tooth shapes (fe/ToothAxesFromShape.h: crown axis, oriented by the arch and the bone).
#include "cli/Commands.h"
#include "fe/ToothAxesFromShape.h"
#include "io/Case.h"
#include "io/Error.h"
#include "io/ToothAxes.h"
#include "levelset/JawInput.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>

namespace jawmesh {
namespace {

struct AxesCliOptions {
    std::string caseDir;
    std::string jaw;
    bool json = false;
    bool computed = false;
    std::string output;
};

void runAxes(const AxesCliOptions& opt, const GlobalOptions& global) {
    const CaseInfo info = discoverCase(opt.caseDir);
    std::map<int, ToothAxes> all;
    nlohmann::json sources = nlohmann::json::object();
    for (const JawCase& jc : info.jaws) {
        if (!opt.jaw.empty() && jawName(jc.jaw) != opt.jaw) continue;
        const JawSurfaces surfaces = loadJawInput(jc, LoadOptions(), terminalProgress(global));
        std::vector<std::string> notes;
        const bool fromCase = !surfaces.axes.empty() && !opt.computed;
        const std::map<int, ToothAxes> axes =
            fromCase ? surfaces.axes : toothAxesFromShape(surfaces.teeth, jc.jaw, surfaces.bone, {}, &notes);
        sources[jawName(jc.jaw)] = fromCase ? jc.axesPath : "computed from the tooth shapes";
        if (!global.quiet)
            for (const std::string& n : notes) std::cerr << "note: " << n << "\n";
        all.insert(axes.begin(), axes.end());
    }
    if (sources.empty()) throw Error(opt.caseDir, "case has no " + opt.jaw);
    if (!opt.output.empty()) writeToothAxes(all, opt.output);
    if (opt.json) {
        // The teeth_axes JSON shape: per UNN the crown centre and the end points of the unit axes.
        nlohmann::json root = nlohmann::json::object();
        auto point = [](const Vec3& p) { return nlohmann::json::array({p.x(), p.y(), p.z()}); };
        for (const auto& [unn, a] : all)
            root[std::to_string(unn)] = {{"c", point(a.crownCentre)},
                                         {"x", point(a.crownCentre + a.mesialDistal)},
                                         {"y", point(a.crownCentre + a.labial)},
                                         {"z", point(a.crownCentre + a.occlusal)}};
        std::cout << root.dump(2) << std::endl;
        return;
    }
    for (const auto& [jaw, source] : sources.items()) std::printf("%s: %s\n", jaw.c_str(), source.get<std::string>().c_str());
    for (const auto& [unn, a] : all)
        std::printf("tooth %2d  c (%.2f, %.2f, %.2f)  occlusal (%.3f, %.3f, %.3f)  labial (%.3f, %.3f, %.3f)\n", unn,
                    a.crownCentre.x(), a.crownCentre.y(), a.crownCentre.z(), a.occlusal.x(), a.occlusal.y(), a.occlusal.z(),
                    a.labial.x(), a.labial.y(), a.labial.z());
}

void addAxesCommand(CLI::App& app, GlobalOptions& global) {
    auto opt = std::make_shared<AxesCliOptions>();
    auto* cmd = app.add_subcommand(
        "axes",
        "Tooth axes of a case (crown centre; x mesial->distal, y labial, z occlusal): from its teeth_axes JSON when "
        "present, else computed from the tooth shapes (clinical crown axis: the volume's principal axis in the plane of the labial face, mandibular molars the principal axis itself; oriented by the arch and the bone).");
    cmd->add_option("case", opt->caseDir, "Case folder (Open-Full-Jaw layout)")->required()->check(CLI::ExistingDirectory);
    cmd->add_option("--jaw", opt->jaw, "Only this jaw")->check(CLI::IsMember({"mandible", "maxilla"}));
    cmd->add_flag("--json", opt->json, "Print the axes as JSON in the teeth_axes shape");
    cmd->add_flag("--computed", opt->computed, "Compute from the shapes even when the case has an axes file");
    cmd->add_option("-o,--output", opt->output, "Also write the axes JSON to this file");
    cmd->callback([opt, &global] { runAxes(*opt, global); });
}

}  // namespace
JAWMESH_COMMAND(65, addAxesCommand);
}  // namespace jawmesh
