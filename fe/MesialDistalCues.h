// Where a tooth's mesial-distal axis comes from (docs/DESIGN.md, "Tooth axes"): the cues a
// clinician reads, each a direction perpendicular to the tooth's long axis.
//  - Arch tangent: the arch curve through the crown centres, a quadratic fitted to the tooth and
//    its neighbours (5 in UNN order), differentiated at the tooth. A chord between the two
//    neighbours follows the arch only where it is straight: on patient 26 it was 13-19 degrees off
//    on teeth beside the canines and on the first molars.
//  - Crown outline: the principal axes of the occlusal end of the crown (its top 15 %), seen along
//    the long axis. Incisors and canines are wide mesially-distally there (the incisal edge),
//    premolars narrow (buccal and lingual cusps side by side); the axis nearer the arch tangent is
//    the tooth's own mesial-distal direction, which follows a tooth rotated against the arch.
//    Trusted only when the outline is elongated (variance ratio >= 1.8; molar tables are square)
//    and within 30 degrees of the arch (patient 26's rotated incisors and premolars: up to 21).
//  - Buccal cusps (molars): the line through the two most labial of the four highest cusp tips.
//    Trusted within 10 degrees of the arch tangent: a third molar's irregular cusps gave 13-30
//    degree diagonals on patient 26, the first and second molars' lines 4-7.
#pragma once

#include "io/SurfaceMesh.h"

#include <string>
#include <vector>

namespace jawmesh {

/// Unit arch tangents at each point of `crownCentres` (in arch order), in the plane perpendicular
/// to `occlusalNormal`, pointing along the order: the derivative of a least-squares quadratic
/// (parametrised by chord length) through a window of `window` consecutive centres around the
/// point. Fewer than 2 centres: an empty result. Cost O(n).
std::vector<Vec3> archTangents(const std::vector<Vec3>& crownCentres, const Vec3& occlusalNormal, int window = 5);

/// The crown's occlusal outline seen along `occlusal`: its two principal directions (unit,
/// perpendicular to occlusal) and the ratio of their area-weighted variances (>= 1).
struct CrownOutline {
    Vec3 major = Vec3::Zero();
    Vec3 minor = Vec3::Zero();
    double varianceRatio = 1;
};

/// Outline of the surface of `mesh` within `topFraction` of the tooth's length from its occlusal
/// end (triangles by their centroid). A ratio of 1 when that part has no extent. Cost O(triangles).
CrownOutline occlusalOutline(const SurfaceMesh& mesh, const Vec3& occlusal, double topFraction = 0.15);

/// Up to `count` cusp tips, highest first: vertices with no higher vertex (along `occlusal`)
/// within `radiusMm`, i.e. local maxima of the crown's height at that scale; unlike the highest
/// points of a band, they stay on the cusps when the long axis tilts by a few degrees (on patient
/// 26's first molar a 7.7 degree tilt turned a band's buccal line by 17 degrees, the maxima's by
/// 0.1). Ties by vertex index. Cost O(vertices log vertices).
std::vector<Vec3> cuspTips(const SurfaceMesh& mesh, const Vec3& occlusal, int count = 4, double radiusMm = 1.0);

/// The mesial-distal direction chosen from the cues above, and which cue gave it.
struct MesialDistalChoice {
    Vec3 direction = Vec3::Zero();  ///< unit, perpendicular to the long axis, along archTangent
    std::string cue;                ///< "arch", "crown outline" or "buccal cusps"
    double offArchDeg = 0;          ///< angle between the choice and the arch tangent
};

/// The tooth's mesial-distal direction for long axis `occlusal`: the crown outline when it is
/// elongated, else for a molar the buccal cusp line when it agrees with the arch, else the arch
/// tangent. `labial` (perpendicular to occlusal, out of the arch) picks the buccal cusps.
MesialDistalChoice chooseMesialDistal(const SurfaceMesh& mesh, const Vec3& occlusal, const Vec3& archTangent,
                                      const Vec3& labial, bool molar);

}  // namespace jawmesh
