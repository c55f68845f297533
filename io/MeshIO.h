// Surface mesh files. Readers accept STL (binary and ASCII), OBJ, PLY (ASCII and binary
// little-endian) and OFF, chosen by extension (case-insensitive); writers produce binary STL,
// binary PLY or OBJ. Every reader validates what it reads: a malformed file (empty, truncated,
// a header that promises more data than there is, NaN/Inf coordinates, indices out of range,
// binary noise) throws Error naming the file and the problem. Writers write to a temporary file
// and rename it, so a failure never leaves a half-written file.
#pragma once

#include "io/SurfaceMesh.h"

#include <string>

namespace jawmesh {

/// Reads a surface mesh; polygons with more than 3 corners are fan-triangulated.
/// Throws Error("<path>: <problem>") for unreadable or malformed files and unknown extensions.
SurfaceMesh readSurface(const std::string& path);

/// Writes a surface mesh; the format follows the extension (.stl binary, .ply binary, .obj).
/// Throws Error on I/O failure or an unknown extension.
void writeSurface(const SurfaceMesh& mesh, const std::string& path);

}  // namespace jawmesh
