// One OpenVDB grid per .vdb file, written atomically and read back with errors that name the file
// (the carved field, levelset/LabelFieldIO.h, and a jaw's input level sets, JawLevelSetsIO.h).
#pragma once

#include <openvdb/openvdb.h>

#include <string>

namespace jawmesh {

/// Writes `grid` alone into `path` (a temporary name, then renamed). Throws Error on I/O failure.
void writeGridFile(openvdb::GridBase::Ptr grid, const std::string& path);

/// Reads the only grid of `path`. Throws Error naming the file when it cannot be read or holds
/// more or fewer than one grid.
openvdb::GridBase::Ptr readGridFile(const std::string& path);

}  // namespace jawmesh
