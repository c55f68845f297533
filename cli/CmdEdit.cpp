// jawmesh edit: a carved jaw's level sets + an edit file -> the edited jaw carved again, as a
// level-set folder that `jawmesh run <case> --from-vdb` meshes (issue #24).
#include "cli/Commands.h"
#include "io/AtomicFile.h"
#include "io/Edits.h"
#include "io/Error.h"
#include "io/StagedFolder.h"
#include "levelset/JawEdits.h"
#include "levelset/JawLevelSetsIO.h"
#include "levelset/LabelFieldIO.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <memory>

namespace jawmesh {
namespace {

struct EditCliOptions {
    std::string levelSetsDir;
    std::string edits;
    std::string output;
    bool json = false;
};

void runEdit(const EditCliOptions& opt, const GlobalOptions& global) {
    Progress& progress = terminalProgress(global);
    const EditList edits = readEditFile(opt.edits);
    StoredJawLevelSets stored = readJawLevelSets(opt.levelSetsDir + "/input");
    nlohmann::json history = readEditHistory(opt.levelSetsDir);
    history.push_back(applyEdits(edits, stored.levelSets, stored.carve, progress));
    CarveSummary summary;
    const LabelField field = carveJaw(stored.jaw, *stored.levelSets.bone, stored.levelSets.teeth, stored.carve, summary, progress);

    StagedFolder staged(opt.output);
    writeEditableFolder(field, stored.levelSets, stored.jaw, stored.carve, history, staged.path());
    nlohmann::json j = toJson(summary);
    j["options"] = toJson(stored.carve);
    j["edits"] = history;
    writeFileAtomically(staged.path() + "/summary.json", [&](std::ostream& o) { o << j.dump(2) << '\n'; }, false);
    staged.commit(StagedFolder::Mode::Replace);
    if (opt.json) std::cout << j.dump() << std::endl;
    if (!global.quiet)
        for (const auto& w : summary.warnings) std::cerr << "warning: " << w << "\n";
}

void addEditCommand(CLI::App& app, GlobalOptions& global) {
    auto opt = std::make_shared<EditCliOptions>();
    auto* cmd = app.add_subcommand(
        "edit",
        "Clinical what-ifs on a carved jaw: extraction (empty or healed socket), horizontal bone loss, an angular "
        "defect, a tooth's PDL thickness, an implant in place of a tooth. Reads a level-set folder written by `run --write-levelsets` or `carve` (<out>/<jaw>/levelsets), "
        "applies the edit file's edits in order to its input level sets, carves again and writes a level-set folder "
        "for `run <case> --from-vdb`");
    cmd->add_option("levelsets", opt->levelSetsDir, "Level-set folder (with its input/ subfolder)")
        ->required()
        ->check(CLI::ExistingDirectory);
    cmd->add_option("--edits", opt->edits, "JSON edit file: {\"edits\": [{\"op\": \"extract\", \"tooth\": 30}, ...]}")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", opt->output, "Output level-set folder")->required();
    cmd->add_flag("--json", opt->json, "Also print the carve summary and the edits as one JSON object on stdout");
    cmd->callback([opt, &global] { runEdit(*opt, global); });
}

}  // namespace
JAWMESH_COMMAND(35, addEditCommand);
}  // namespace jawmesh
