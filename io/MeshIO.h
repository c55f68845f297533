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

/// Parses a surface held in memory, exactly as readSurface() parses a file; `name` picks the format
/// by its extension and names the data in messages. Throws Error(name, problem). Cost: O(bytes).
SurfaceMesh readSurfaceFromMemory(const std::string& data, const std::string& name);

/// Writes a surface mesh; the format follows the extension (.stl binary, .ply binary, .obj).
/// Throws Error on I/O failure or an unknown extension.
void writeSurface(const SurfaceMesh& mesh, const std::string& path);

/// Lower-case extension of a path without the dot ("STL" -> "stl"); empty when there is none.
/// Cost: O(path length).
std::string surfaceExtension(const std::string& path);

/// True for an extension readSurface() reads: "stl", "obj", "ply", "off" (lower case).
bool isSurfaceExtension(const std::string& extension);

}  // namespace jawmesh
