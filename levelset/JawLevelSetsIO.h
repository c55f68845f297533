// A jaw's input level sets and the carve's options, kept beside its carved field so that the jaw
// can be edited and carved again (`jawmesh edit`, levelset/JawEdits.h):
//   <dir>/bone.vdb, <dir>/tooth_<UNN>.vdb   the level sets carving started from (edits applied)
//   <dir>/carve.json                        {"jaw", "options": toJson(CarveOptions)}
//   <dir>/teeth_axes.json                   the case's tooth axes, when it had them
#pragma once

#include "io/Labels.h"
#include "levelset/CarveGaps.h"
#include "levelset/JawLevelSets.h"

#include <string>

namespace jawmesh {

/// Writes the folder (created if missing), each file atomically. Throws Error on I/O failure.
void writeJawLevelSets(const JawLevelSets& levelSets, Jaw jaw, const CarveOptions& carve, const std::string& dir);

struct StoredJawLevelSets {
    Jaw jaw = Jaw::Mandible;
    JawLevelSets levelSets;
    CarveOptions carve;  ///< with the axes of teeth_axes.json
};

/// Reads a folder written by writeJawLevelSets. Throws Error naming the file when carve.json or
/// bone.vdb is missing or unreadable, or a grid is not a level set on the bone's transform.
StoredJawLevelSets readJawLevelSets(const std::string& dir);

}  // namespace jawmesh
