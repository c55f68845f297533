// From a label volume to the surfaces the pipeline reads (issue #23): each role's voxels (bone,
// each tooth; io/LabelRoles.h) become a smooth closed surface in world millimetres, then carving
// and everything after it run as for surface input.
//  - A role's voxels give a level set whose zero set is their boundary (OpenVDB
//    topologyToLevelSet in voxel index space, no closing), smoothed by `smoothingSteps` mean
//    filters (3x3x3, LevelSetFilter) so the staircase goes while the surface stays within a
//    fraction of a voxel of the label boundary; extracted by volumeToMesh and mapped to world by
//    the volume's voxel-to-world map (anisotropic and oblique spacing included).
//  - Segmented PDL labels are meshed as bone when the PDL is regenerated (the carve then cuts the
//    PDL at the requested thickness, as for surfaces).
#pragma once

#include "io/Case.h"
#include "io/LabelRoles.h"
#include "io/LabelVolume.h"
#include "io/Progress.h"

#include <vector>

namespace jawmesh {

/// The surface of the voxels of the given segments (indices into volume.segments), outward.
/// Throws Error naming the volume when they hold no voxel. Cost: linear in the segments' voxels.
SurfaceMesh labelSurface(const LabelVolume& volume, const std::vector<std::size_t>& segments, int smoothingSteps = 2);

/// Bone and tooth surfaces of a jaw's label volume under `roles` (PDL segments go to the bone
/// when roles.pdl is Generate; Keep is refused with a message until the kept PDL is meshed).
/// Teeth are processed in parallel (TBB), each deterministically. Throws Error naming the volume.
JawSurfaces surfacesFromLabelVolume(const LabelVolume& volume, const LabelAssignment& roles, Jaw jaw,
                                    Progress& progress = noProgress());

}  // namespace jawmesh
