// Tooth axes computed from the tooth shapes when a case has no axes file (docs/DESIGN.md): the long
// axis is the principal axis of largest spread of the tooth volume, oriented toward the occlusal
// side; the mesial-distal axis follows the arch (neighbours in UNN order) and points distally; the
// labial axis completes the frame, pointing away from the inside of the arch.
#pragma once

#include "io/Labels.h"
#include "io/SurfaceMesh.h"
#include "io/ToothAxes.h"

#include <map>
#include <string>
#include <vector>

namespace jawmesh {

struct AxesFromShapeOptions {
    /// The crown is the part of the tooth within this fraction of its length (along the long axis)
    /// from the occlusal end; its volume centroid is the crown centre "c". 0.45 puts c where the
    /// published Open-Full-Jaw axes have it (about a quarter of the length from the tip).
    double crownFraction = 0.45;
};

/// Axes of every tooth of one jaw, in the ToothAxes convention (x distal, y labial, z occlusal).
/// @param teeth  closed tooth surfaces by UNN (either orientation), mm
/// @param jaw    the jaw of the teeth (numbering and the fallback "occlusal = +z mandible, -z maxilla")
/// @param bone   the jaw's bone surface, may be empty; when given, the occlusal side is where the
///               crowns stick out of it, else where the tooth volume is bulkier (the crown)
/// @param notes  receives a line per decision a person should know (fallbacks), may be null
/// The occlusal sense is decided for the whole jaw by a vote of the teeth, then every long axis is
/// turned to agree with it. With a single tooth, the labial sense cannot come from the arch and
/// is a guess (noted). Throws Error for an empty or zero-volume tooth.
/// Cost: O(triangles).
std::map<int, ToothAxes> toothAxesFromShape(const std::map<int, SurfaceMesh>& teeth, Jaw jaw, const SurfaceMesh& bone,
                                            const AxesFromShapeOptions& options = {},
                                            std::vector<std::string>* notes = nullptr);

/// Angle in degrees between two directions (0..180).
double angleDeg(const Vec3& a, const Vec3& b);

}  // namespace jawmesh
