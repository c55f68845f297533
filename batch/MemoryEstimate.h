// How much memory one jaw's run needs, estimated before running it, so that a batch starts a case
// only when it fits beside the ones already running.
//
// The rule. A run's peak is set by its grids and surfaces at the level-set voxel size h: the
// narrow bands, the label field and the interface surface all grow with the number of voxels the
// surfaces cross, i.e. with the input surface area A over h^2. So
//     estimate = 150 MB + 700 bytes x A / h^2            (A in mm^2, h in mm)
// It stays above every measured peak (docs/BENCHMARKS.md, sessions 13 and "Batch"), with room for
// anatomy denser than the shared cases: shared mandible at 0.05 mm (A = 23,061 mm^2: 2.93 GB
// measured, 6.6 GB estimated), shared maxilla (11,855 mm^2: 2.08 GB, 3.5 GB), the demo's 2-tooth
// phantom at 0.05 mm (2,924 mm^2: 0.45 GB, 0.97 GB); the 1-tooth phantom at 0.1 and 0.2 mm
// (2,543 mm^2: 195 and 106 MB measured before session 13; 328 and 195 MB).
// Until session 13 the factor was 1,200 (the mandible peaked at 9.6 GB).
// Reading the surfaces to get A costs about a second per million triangles.
#pragma once

#include "io/Case.h"
#include "io/SurfaceMesh.h"

#include <cstdint>
#include <string>

namespace jawmesh {

/// Total triangle area, mm^2 (a triangle soup's duplicated faces count twice).
double surfaceAreaMm2(const SurfaceMesh& mesh);

/// The rule above, in bytes. voxelMm must be > 0.
std::uint64_t estimateRunMemoryBytes(double inputAreaMm2, double voxelMm);

/// The rule above for one jaw's input surfaces (bone and teeth), bytes. voxelMm must be > 0.
std::uint64_t estimateJawMemoryBytes(const JawSurfaces& surfaces, double voxelMm);

/// Refuses a run up front: throws Error(where, ...) stating the estimate, the available memory and
/// the smallest voxel that would fit when estimateJawMemoryBytes() exceeds availableBytes
/// (0 = unknown: no check). Cost: one pass over the triangles.
void requireMemoryFits(const JawSurfaces& surfaces, double voxelMm, std::uint64_t availableBytes, const std::string& where);

/// Memory the batch may use now, bytes: /proc/meminfo MemAvailable, capped by the cgroup (v2 or v1)
/// limit minus its current use when one is set. 0 when neither can be read.
std::uint64_t availableMemoryBytes();

}  // namespace jawmesh
