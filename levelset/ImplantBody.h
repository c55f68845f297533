// An implant's level set (issue #24): a cylindrical or screw-form body along a tooth's long axis,
// its top (the platform) at a height on the axis, and with a crown the natural tooth's crown on an
// abutment of the body's radius: the abutment stands a collar clear of the crest, then the crown
// flares out of it at 45 degrees (one region: implant, abutment and crown). Carving
// fuses it to the bone (CarveOptions::implants: a tooth with no PDL).
//
// Distances: the body is a capped cylinder whose radius may vary with depth; for a cylinder its
// signed distance is exact, for a screw thread (radius varying with depth) the lateral distance is
// divided by the profile's slope and the band is re-normalised. Body and crown are joined by min /
// max (exact on the zero set, as levelset/Csg.h).
#pragma once

#include "io/Edits.h"
#include "levelset/ToothLongAxis.h"

#include <openvdb/openvdb.h>

namespace jawmesh {

struct ImplantPlacement {
    LongAxis axis;          ///< the tooth's long axis (root to crown)
    double platformMm = 0;  ///< height of the body's top along the axis, mm
    double crestMm = 0;     ///< height of the crest: the abutment rises from the platform to it, the crown sits above
};

/// Radius of the body (mm) at depthMm below the platform (0..lengthMm): the diameter's half for a
/// cylinder; a screw's radius falls by threadDepthMm between thread crests threadPitchMm apart.
double implantRadiusMm(const ImplantEdit& implant, double depthMm);

/// Volume of the body below the platform, mm^3 (a cylinder's pi r^2 L; a screw's integral of its
/// radius profile): what the meshed implant's part below the platform is checked against.
double implantBodyVolumeMm3(const ImplantEdit& implant);

/// The implant's level set on `tooth`'s transform and band (tooth: the natural tooth it replaces,
/// its crown taken when implant.crown). Throws Error for a grid that is not a level set. Cost: one
/// pass over the voxels of the body's and the tooth's boxes (serial; a screw adds a re-normalisation).
openvdb::FloatGrid::Ptr implantLevelSet(const ImplantEdit& implant, const ImplantPlacement& at,
                                        const openvdb::FloatGrid& tooth);

}  // namespace jawmesh
