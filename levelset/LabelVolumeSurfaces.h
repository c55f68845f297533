// From a label volume to the surfaces the pipeline reads (issue #23): each role's voxels (bone,
// each tooth; io/LabelRoles.h) become a smooth closed surface in world millimetres, then carving
// and everything after it run as for surface input.
//  - A role's voxels give an indicator (-0.5 inside, +0.5 outside, a narrow band in voxel index
//    space) smoothed by `smoothingSteps` box means, each followed by putting every voxel centre
//    back on its side (constrained smoothing), so the staircase goes while the surface stays
//    within a voxel of the label boundary; its iso value is then set so that the surface encloses
//    the voxels' volume (smoothing rounds convex parts inward), except when a segmented PDL is
//    kept (its walls would move into it; iso 0 keeps flat faces on the voxel faces). Extracted by volumeToMesh and
//    mapped to world by the volume's voxel-to-world map (anisotropic and oblique spacing included).
//  - Segmented PDL labels are left out of the bone when they are kept ("pdl": "keep", the
//    default): the PDL is then the gap between each root and its socket, which carving keeps
//    (levelset/CarveGaps.h keptPdlCarveOptions). When the PDL is regenerated they are meshed as
//    bone, and the carve cuts the PDL at the requested thickness, as for surfaces.
#pragma once

#include "io/Case.h"
#include "io/LabelRoles.h"
#include "io/LabelVolume.h"
#include "io/Progress.h"

#include <vector>

namespace jawmesh {

/// Box means of the constrained smoothing: 2 take the staircase away (more only round more).
constexpr int kLabelSmoothingSteps = 2;

/// The surface of the voxels of the given segments (indices into volume.segments), outward.
/// Throws Error naming the volume when they hold no voxel. Cost: linear in the segments' voxels.
SurfaceMesh labelSurface(const LabelVolume& volume, const std::vector<std::size_t>& segments,
                         int smoothingSteps = kLabelSmoothingSteps);

/// Bone and tooth surfaces of a jaw's label volume under `roles`: PDL segments go to the bone
/// when roles.pdl is Generate, and are left out of it when kept (JawSurfaces::pdlKept).
/// Teeth are processed in parallel (TBB), each deterministically. Throws Error naming the volume.
/// The volume's values are released once its segments' masks are made (the smoothing needs only
/// the masks: a 0.1 mm jaw's 600 M voxels are not held beside it).
JawSurfaces surfacesFromLabelVolume(LabelVolume&& volume, const LabelAssignment& roles, Jaw jaw,
                                    Progress& progress = noProgress());

}  // namespace jawmesh
