// Worked example of a clinical what-if through jawmesh's library (issue #24,
// examples/edit_levelsets/README.md): extract one tooth from a carved jaw, leaving its socket empty
// or healed, carve again and write a level-set folder that `jawmesh run <case> --from-vdb` meshes.
// The same as `jawmesh edit <levelsets> --edits <file> -o <out>` with one extract edit; a program
// of your own can build any edit list this way (levelset/JawEdits.h, io/Edits.h).
#include "io/Edits.h"
#include "io/Error.h"
#include "io/StagedFolder.h"
#include "levelset/JawEdits.h"
#include "levelset/JawLevelSetsIO.h"
#include "levelset/LabelFieldIO.h"

#include <openvdb/openvdb.h>

#include <filesystem>
#include <iostream>
#include <string>

namespace fs = std::filesystem;
using namespace jawmesh;

int main(int argc, char** argv) {
    const bool healed = argc == 5 && std::string(argv[4]) == "--healed";
    if (argc != 4 && !healed) {
        std::cerr << "usage: remove_tooth <levelsets dir> <tooth UNN> <output dir> [--healed]\n";
        return 2;
    }
    const std::string in = argv[1], out = argv[3];
    try {
        openvdb::initialize();
        if (fs::exists(out)) throw Error(out, "exists already; choose a new folder");
        // The edit, as an edit file would give it.
        const nlohmann::json entry = {{"op", "extract"}, {"tooth", std::stoi(argv[2])}, {"socket", healed ? "healed" : "empty"}};
        const EditList edits = parseEdits({{"edits", {entry}}}, "remove_tooth");
        // The level sets carving started from, edited, carved again.
        StoredJawLevelSets jaw = readJawLevelSets(in + "/input");
        nlohmann::json history = readEditHistory(in);
        history.push_back(applyEdits(edits, jaw.levelSets, jaw.carve));
        CarveSummary summary;
        const LabelField field = carveJaw(jaw.jaw, *jaw.levelSets.bone, jaw.levelSets.teeth, jaw.carve, summary);
        // Everything goes to a staging folder renamed at the end: no half-written result.
        StagedFolder staged(out);
        writeEditableFolder(field, jaw.levelSets, jaw.jaw, jaw.carve, history, staged.path());
        staged.commit(StagedFolder::Mode::Replace);
        std::cout << "extracted tooth " << argv[2] << " (socket " << entry["socket"].get<std::string>() << "); grids in " << out << "\n";
    } catch (const std::exception& e) {
        std::cerr << "remove_tooth: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
