// Tooth axes computed from the tooth shapes when a case has no axes file (docs/DESIGN.md).
//  - Anatomical axis: the principal axis of largest spread of the tooth volume, oriented toward the
//    occlusal side (one sense for the whole jaw, by a vote of the teeth).
//  - Mesial-distal axis: from the crown's own shape where it shows one, else the arch curve
//    (fe/MesialDistalCues.h: crown outline, buccal cusps of molars, arch tangent), points
//    distally; the labial axis completes the frame, pointing away from the inside of the arch.
//    Which cue each tooth used, and how far it turned from the arch, goes to `notes`.
//  - Crown centre: volume centroid of the crown part (the occlusal end of the tooth).
//  - Long (occlusal) axis: the clinical crown axis (Andrews' FACC): the anatomical axis turned into
//    the plane of the labial face, where the labial axis from the crown centre leaves the crown. A
//    clinician places the long axis along the crown he sees; on teeth whose root is inclined
//    against the crown (canines, incisors) that differs by 10-16 degrees from any whole-tooth axis.
//    Mandibular molars keep the anatomical axis (their buccal face leans lingually; see the options).
//  - Checked against the neighbours: a long axis more than kMaxNeighbourLongAxisDeg from the nearer
//    of its neighbours' along the arch (which agree with each other) is not used; the tooth takes
//    their mean and is reported as uncertain (a shape whose largest spread is not its length, such
//    as a short or half-erupted molar, turns the anatomical axis far off: a held-out mandible's
//    last molar came out 44 degrees from its clinician axis).
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
    /// Radius of the patch of labial crown surface whose mean normal gives the plane of the labial
    /// face: most of a crown's labial face, so the mean follows the face, not its bumps or the
    /// cusp slopes above it (on patient 26, 1.5 mm: worst long axis 16 degrees off; 3-4 mm: 7-10).
    /// 0 keeps the anatomical axis as the long axis.
    double labialFaceRadiusMm = 3.5;
    /// The same for molars, whose buccal face is about 10 mm wide (incisors to premolars 6.5-8.5):
    /// on patient 26's molars 2.5-3.5 mm left the third molar's long axis 10 degrees off, 4.5-5
    /// mm brought every molar within 7.3.
    double molarLabialFaceRadiusMm = 4.5;
    /// The same for mandibular molars; 0 (the default) keeps their anatomical axis. A lower
    /// molar's buccal face leans lingually from its cervical bulge to its cusps, so its plane is no
    /// guide to the long axis: on Open-Full-Jaw patient 26's mandible the face put molars 18, 19
    /// and 30 12-20 degrees from the clinician axes, the anatomical axis 4-9; on the phantom 2.4-4.3
    /// against 0.5-0.9. (Maxillary molars need the face: their palatal root tilts the volume's axis.)
    double mandibularMolarLabialFaceRadiusMm = 0.0;
};

/// Axes of every tooth of one jaw, in the ToothAxes convention (x distal, y labial, z occlusal).
/// @param teeth  closed tooth surfaces by UNN (either orientation), mm
/// @param jaw    the jaw of the teeth (numbering and the fallback "occlusal = +z mandible, -z maxilla")
/// @param bone   the jaw's bone surface, may be empty; when given, the occlusal side is where the
///               crowns stick out of it, else where the tooth volume is bulkier (the crown)
/// @param notes  receives a line per decision a person should know (fallbacks), may be null
/// With a single tooth, the labial sense cannot come from the arch and is a guess (noted). A tooth
/// whose labial face cannot be found (the labial ray misses the crown, or meets a face that is not
/// a side of the tooth) keeps its anatomical axis (noted). Throws Error for an empty or
/// zero-volume tooth. Cost: O(triangles).
std::map<int, ToothAxes> toothAxesFromShape(const std::map<int, SurfaceMesh>& teeth, Jaw jaw, const SurfaceMesh& bone,
                                            const AxesFromShapeOptions& options = {},
                                            std::vector<std::string>* notes = nullptr);

/// Neighbouring teeth's long axes differ by up to 25 degrees on the shared mandible (the curve of
/// Wilson: first molar against second premolar) and 18 between nearest neighbours.
constexpr double kMaxNeighbourLongAxisDeg = 30.0;
/// The words in the note of a tooth whose axes its neighbours contradicted (a run copies such notes
/// into run.json's warnings).
constexpr const char* kUncertainAxesNote = "axes uncertain";

/// Angle in degrees between two directions (0..180).
double angleDeg(const Vec3& a, const Vec3& b);

}  // namespace jawmesh
