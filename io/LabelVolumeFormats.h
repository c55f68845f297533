// The two file formats behind io/LabelVolume.h (internal to io/): each fills or writes the
// volume's size, layers, voxel-to-world map and values; LabelVolume.cpp checks and counts.
#pragma once

#include "io/LabelVolume.h"

#include <map>
#include <string>

namespace jawmesh {

/// NRRD through Teem. `keyValues` receives the header's key/value pairs (Slicer's segment
/// metadata among them). Throws Error naming the file.
LabelVolume readNrrdVolume(const std::string& path, std::map<std::string, std::string>& keyValues);
void writeNrrdVolume(const LabelVolume& volume, const std::map<std::string, std::string>& keyValues,
                     const std::string& path);

/// NIfTI-1 and NIfTI-2 through nifti2. Throws Error naming the file.
LabelVolume readNiftiVolume(const std::string& path);
void writeNiftiVolume(const LabelVolume& volume, const std::string& path);

/// True when every value fits an unsigned 16-bit label (the writers' smaller type).
bool fitsUint16(const std::vector<std::int32_t>& values);

/// Converts `count` integer values of a file's element type to int32 into out[0..count) (or into
/// `out` resized to count); false for a type that is not an integer of 8-32 bits and for uint32
/// values above INT32_MAX (out is then partly written).
enum class VoxelType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Other };
bool convertValues(const void* data, VoxelType type, std::size_t count, std::int32_t* out);
bool convertValues(const void* data, VoxelType type, std::size_t count, std::vector<std::int32_t>& out);

}  // namespace jawmesh
