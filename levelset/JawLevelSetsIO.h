// A jaw's input level sets and the carve's options, kept beside its carved field so that the jaw
// can be edited and carved again (`jawmesh edit`, levelset/JawEdits.h), and the edits so far:
//   <dir>/bone.vdb, <dir>/tooth_<UNN>.vdb   the level sets carving started from (edits applied)
//   <dir>/implant_<UNN>.vdb                  an implant in place of tooth UNN (CarveOptions::implants)
//   <dir>/carve.json                        {"jaw", "options": toJson(CarveOptions)}
//   <dir>/teeth_axes.json                   the case's tooth axes, when it had them
// in <folder>/input beside the carved field (LabelFieldIO.h) in <folder>, and <folder>/edits.json.
#pragma once

#include "io/Labels.h"
#include "levelset/CarveGaps.h"
#include "levelset/JawLevelSets.h"
#include "levelset/LabelField.h"

#include <nlohmann/json.hpp>

#include <string>

namespace jawmesh {

/// Writes the folder (created if missing), each file atomically. Throws Error on I/O failure.
void writeJawLevelSets(const JawLevelSets& levelSets, Jaw jaw, const CarveOptions& carve, const std::string& dir);

/// The record of every edit file applied to a level-set folder, oldest first (a JSON array of
/// applyEdits' records), kept in the folder under this name; run.json's "edits" is the same array.
inline constexpr const char* kEditHistoryFile = "edits.json";

/// The edit history of a level-set folder (an empty array when it has none). Throws Error naming
/// the file when it is not a JSON array.
nlohmann::json readEditHistory(const std::string& dir);

/// Writes the history into dir (atomically).
void writeEditHistory(const nlohmann::json& history, const std::string& dir);

/// The whole editable folder: the carved field in dir, the input level sets and options in
/// dir/input, the history (when not empty) in dir/edits.json. What `carve`, `run
/// --write-levelsets` and `edit` write.
void writeEditableFolder(const LabelField& field, const JawLevelSets& levelSets, Jaw jaw, const CarveOptions& carve,
                         const nlohmann::json& history, const std::string& dir);

struct StoredJawLevelSets {
    Jaw jaw = Jaw::Mandible;
    JawLevelSets levelSets;
    CarveOptions carve;  ///< with the axes of teeth_axes.json
};

/// Reads a folder written by writeJawLevelSets. Throws Error naming the file when carve.json or
/// bone.vdb is missing or unreadable, or a grid is not a level set on the bone's transform.
StoredJawLevelSets readJawLevelSets(const std::string& dir);

}  // namespace jawmesh
