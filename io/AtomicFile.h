// Write-then-rename, so a crash or an error in the middle never leaves a half-written output.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace jawmesh {

/// Calls write() on a stream to "<path>.tmp-<pid>" and renames it to path when write() returns
/// and the stream is still good. On any exception or stream failure the temporary file is removed
/// and Error is thrown (or the exception rethrown). Parent folders are created.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         bool binary = true);

/// For writers that need a file name (e.g. OpenVDB): write(tmpPath) must create tmpPath; it is then
/// renamed to path, or removed if write() throws.
void writeFileAtomicallyByName(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace jawmesh
