// Grid measurements of a carved jaw (helper of CarveGaps.h, usable on any LabelField, e.g. one read
// back from .vdb files after a user edit): PDL thickness, volumes, root/crown surface split.
#pragma once

#include "levelset/CarveGaps.h"
#include "levelset/LabelField.h"

#include <openvdb/openvdb.h>

namespace jawmesh {

/// Measures tooth unn of a label field and fills everything in `out` except `unn` bookkeeping:
///  * thickness: at every tooth-side PDL interface point (tooth_unn voxel next to a pdl_unn voxel,
///    placed on the zero crossing of the tooth distance), the distance to the nearest bone-side
///    interface point (pdl_unn voxel next to bone, on the zero crossing of the bone distance).
///    Points closer than capExclusionMm to a PDL face that borders anything but tooth, PDL or bone
///    (the cap at the crest, the clearance to other teeth) are excluded.
///  * volumes (voxel counts, tiles included) of tooth and PDL; rootAreaFraction = tooth voxel faces
///    towards its PDL / all tooth boundary faces; impacted = PDL has no face to the outside.
/// out.implant selects implantLabel(unn) for the tooth (its PDL figures are then 0).
/// Uses labels and the distances of toothLabel(unn) and the bone (sub-voxel interface placement;
/// voxel centres are used where a distance grid is missing).
/// Throws Error for an invalid unn or a field without labels. Cost: one pass over the voxels of
/// the tooth's PDL and its neighbours plus nearest-point queries (TBB); deterministic.
void measureTooth(const LabelField& field, int unn, double capExclusionMm, ToothCarveSummary& out);

}  // namespace jawmesh
