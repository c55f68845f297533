// The synthetic jaw phantom as implicit functions (helper of Phantom.h): a dental arch, tooth
// shapes built from tapered superelliptic cross-sections, cusps and round-cone roots, and an arch
// shaped alveolar bone body. Every field is negative inside, positive outside, in millimetres and
// close to a distance near its zero set (Lipschitz constant at most ~2), so it can be sampled into a
// narrow-band level set. The frame is the one the case files use: +x patient left, +y posterior,
// +z superior; the mandible is built with crowns up, the maxilla is the same construction mirrored
// in z above it.
#pragma once

#include "io/Labels.h"
#include "io/SurfaceMesh.h"
#include "io/ToothAxes.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace jawmesh::phantom {

enum class ToothKind { CentralIncisor, LateralIncisor, Canine, FirstPremolar, SecondPremolar, FirstMolar, SecondMolar, ThirdMolar };

/// A cusp on an occlusal table: a Gaussian bump of the crown top, local coordinates (mm).
struct Cusp {
    double u = 0, v = 0, height = 0, sigma = 1;
};

/// One separate root of a multi-rooted tooth: a round cone from top to apex in local coordinates
/// whose labial (v) coordinate is scaled by vScale before the cone test (flattened roots).
struct RootCone {
    Vec3 top = Vec3::Zero(), apex = Vec3::Zero();
    double radiusTop = 1, radiusApex = 0.5, vScale = 1;
};

/// Everything that defines one phantom tooth. Local coordinates (u, v, w): u distal, v labial,
/// w occlusal, origin at the centre of the cemento-enamel junction (crown-root junction).
struct ToothSpec {
    int unn = 0;
    ToothKind kind = ToothKind::CentralIncisor;
    double archS = 0;             ///< signed arc length of the tooth centre along the arch, mm (+ = patient left)
    Vec3 cej = Vec3::Zero();      ///< junction centre, template frame (mandible orientation), mm
    Eigen::Matrix3d frame;        ///< columns: distal, labial, occlusal unit vectors, template frame
    double halfMd = 3, halfBl = 3;           ///< largest crown half widths, mm
    double cervicalMd = 0.7, cervicalBl = 0.9;  ///< cervical half widths as fractions of the largest
    double contourHeightMd = 0.6, contourHeightBl = 0.3;  ///< height of contour, fraction of crown height
    double topMd = 0.9, topBl = 0.8;         ///< half widths at the crown top, fractions of the largest
    double crownHeight = 9;                  ///< junction to incisal edge / cusp tips, mm
    double rootLength = 13;                  ///< junction to apex, mm
    double rootBend = 0.5;                   ///< distal displacement of the apex, mm
    double trunkLength = 0;                  ///< multi-rooted: junction to furcation, mm (0 = one root)
    double crossExponent = 2.2;              ///< superellipse exponent of crown cross-sections
    double cuspSlope = 0;                    ///< canine: top height drop per mm away from the tip
    double fossaDepth = 0;                   ///< premolars / molars: occlusal table below the cusp tips
    std::vector<Cusp> cusps;
    std::vector<RootCone> roots;             ///< separate roots below the trunk (multi-rooted only)
    double inclinationTan = 0;               ///< tan of the labial crown inclination (roots go lingual)
    BBox box;                                ///< conservative template-frame bounds of the tooth, mm
};

/// Where (p.x, p.y) lies along the arch: the same for every point of a vertical line.
struct ArchPosition {
    double s = 0;  ///< arc length, mm
    double n = 0;  ///< signed horizontal offset along labial(s), mm
};

/// The dental arch: a symmetric planar curve z = const sampled by arc length, with a lookup grid
/// for closest-point queries.
class Arch {
public:
    /// Builds the curve for |s| <= halfLength mm, scaled by `scale` (1 = a typical adult mandible).
    Arch(double halfLength, double scale);
    /// Point (z = 0) at signed arc length s (mm; + = patient left), clamped to the curve.
    Vec3 point(double s) const;
    /// Unit distal direction at s (away from the midline along the arch).
    Vec3 distal(double s) const;
    /// Unit labial direction at s (horizontal, away from the inside of the arch).
    Vec3 labial(double s) const;
    /// Closest point of the curve to (p.x, p.y): its arc length s and the signed horizontal offset
    /// n along labial(s). Exact near the curve (within ~10 mm), approximate beyond. O(1).
    ArchPosition closest(const Vec3& p) const;
    double halfLength() const { return halfLength_; }

private:
    double halfLength_, step_;
    std::vector<Eigen::Vector2d> pts_;   // samples at s = -halfLength + i * step
    Eigen::Vector2d gridMin_;
    double cell_;
    int nx_, ny_;
    std::vector<std::int32_t> nearest_;  // sample index per lookup cell
};

/// The phantom of one jaw: tooth specs plus what the bone field needs, all in the template frame
/// (mandible orientation); `mirror` maps world <-> template for the maxilla (z -> -z).
struct JawAnatomy {
    Jaw jaw = Jaw::Mandible;
    bool mirror = false;
    Arch arch{1, 1};
    std::vector<ToothSpec> teeth;  ///< only the selected teeth, in UNN order
    double boneEndS = 20;          ///< the body ends (rounded) at |s| = boneEndS, mm
    double bodyHeight = 27;        ///< crest to base, mm
    double baseExtraHalfWidth = 2.5;  ///< base half thickness minus crest half thickness, mm
    /// Per arch sample: crest height at the arch line, its slope along labial, the crest half
    /// thickness and tan of the inclination (all smoothed along the arch from the teeth).
    std::vector<double> tableS, crestZ, crestSlope, crestHalf, inclTan;
    BBox boneBox;                  ///< template-frame bounds of the bone, mm
};

/// Builds the anatomy of one jaw: all 16 teeth laid out along the arch, the `count` nearest the
/// midline kept (ties: lower UNN first), sizes and angles perturbed by `seed`.
/// Throws Error unless 1 <= count <= 16.
JawAnatomy buildJawAnatomy(Jaw jaw, int count, std::uint32_t seed);

/// Signed field of one tooth at a template-frame point, mm (negative inside). Cost O(cusps + roots).
double toothField(const ToothSpec& tooth, const Vec3& p);

/// Signed field of the bone: the alveolar body minus every tooth, so sockets coincide exactly with
/// the tooth roots. Template-frame point, mm. Cost O(teeth) with bounding-box culling.
double boneField(const JawAnatomy& anatomy, const Vec3& p);

/// boneField at p given anatomy.arch.closest(p) (a vertical line of voxels shares it: the label
/// volume asked the arch once per voxel, a tenth of a phantom label map's time).
double boneField(const JawAnatomy& anatomy, const Vec3& p, const ArchPosition& at);

/// Template-frame point of a world point (and back: the map is its own inverse).
inline Vec3 toTemplate(const JawAnatomy& anatomy, const Vec3& p) {
    return anatomy.mirror ? Vec3(p.x(), p.y(), -p.z()) : p;
}

/// World-frame bounds of a template-frame box.
BBox toWorld(const JawAnatomy& anatomy, const BBox& templateBox);

/// World-frame axes of a tooth, known by construction: crown centre, x distal, y labial, z occlusal.
ToothAxes toothAxes(const JawAnatomy& anatomy, const ToothSpec& tooth);

}  // namespace jawmesh::phantom
