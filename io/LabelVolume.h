// A segmentation's label volume (issue #23): NRRD (.nrrd, .nhdr + data, raw or gzip; 3D Slicer
// .seg.nrrd with its segment metadata and layers) through Teem, NIfTI-1/2 (.nii, .nii.gz) through
// nifti2. Voxel to world from the header (NRRD space directions and origin; NIfTI sform, else
// qform, else pixdim), in millimetres; integer labels of 8-32 bits.
#pragma once

#include "io/SurfaceMesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace jawmesh {

/// One segment of a volume: the voxels of layer `layer` whose value is `value`. A plain label map
/// has one layer and a segment per non-zero value; a Slicer segmentation names its segments.
struct LabelSegment {
    int layer = 0;
    std::int32_t value = 0;
    std::string name;             ///< Slicer's Segment<N>_Name, empty for a plain label map
    std::size_t voxelCount = 0;   ///< voxels carrying it
};

struct LabelVolume {
    std::string path;                          ///< the file read, for messages
    std::array<int, 3> size{0, 0, 0};          ///< voxels along i, j, k
    int layers = 1;                            ///< Slicer layers (4D .seg.nrrd), else 1
    /// World position (mm, the file's own space: RAS or LPS as written) of voxel centre (i, j, k):
    /// origin + directions * (i, j, k); directions' columns are the axes' steps (spacing included).
    Eigen::Matrix3d directionsMm = Eigen::Matrix3d::Identity();
    Vec3 originMm = Vec3::Zero();
    std::vector<std::int32_t> values;          ///< layer-major, then i fastest, then j, then k
    std::vector<LabelSegment> segments;        ///< in value order (plain) or the file's order (Slicer)

    std::size_t voxels() const { return static_cast<std::size_t>(size[0]) * size[1] * size[2]; }
    std::int32_t at(int layer, std::size_t voxel) const { return values[static_cast<std::size_t>(layer) * voxels() + voxel]; }
    Vec3 worldOf(double i, double j, double k) const { return originMm + directionsMm * Vec3(i, j, k); }
};

/// One segment per non-zero value of layer 0, in value order, with its voxel count (no names).
std::vector<LabelSegment> valueSegments(const LabelVolume& volume);

/// True when `path` names a label volume this reader takes (.nrrd, .nhdr, .nii, .nii.gz).
bool isLabelVolumePath(const std::string& path);

/// Reads a label volume; the format comes from the name. Throws Error naming the file for: an
/// unreadable, truncated or corrupt file, a data size that does not match the header, a volume
/// that is not 3D (a 4D one only as a Slicer layered segmentation), floating-point or 64-bit
/// values, a singular or non-finite voxel-to-world map, lengths in metres ("space units" m, NIfTI
/// xyz units metres: with the scale hint) and a volume without any non-zero voxel.
LabelVolume readLabelVolume(const std::string& path);

/// Writes a plain 3D label volume (one layer; uint16 when the values fit, else int32), or with
/// `slicerSegments` a Slicer .seg.nrrd whose segments carry those names (NRRD only). The format
/// comes from the name (.nrrd gzip-encoded, .nii, .nii.gz). Atomic (a temporary file renamed).
/// Throws Error naming the file on failure or for a volume whose values do not match its size.
void writeLabelVolume(const LabelVolume& volume, const std::string& path, bool slicerSegments = false);

}  // namespace jawmesh
