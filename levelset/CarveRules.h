// Internal to carving (levelset/CarveGaps.cpp, CarveToothBands.cpp): the rules' parameters, each
// tooth's working fields and the small per-point rules they share (thickness along the root, the
// apex taper of the erosion, the extended bone distance).
#pragma once

#include "levelset/CarveGaps.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace jawmesh::carve {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::FloatGrid;
using openvdb::Vec3d;
using FloatAcc = FloatGrid::ConstAccessor;


/// Thinnest and thickest PDL asked for anywhere on a root (the profile's, else the uniform one), mm.
inline std::pair<double, double> thicknessRangeMm(const std::optional<PdlProfile>& profile, double uniformMm) {
    if (!profile) return {uniformMm, uniformMm};
    return {std::min({profile->cervical, profile->midRoot, profile->apical}),
            std::max({profile->cervical, profile->midRoot, profile->apical})};
}

/// The same over the jaw's PDL and every tooth's own (CarveOptions::toothPdl).
inline std::pair<double, double> thicknessRangeMm(const CarveOptions& o) {
    auto range = thicknessRangeMm(o.profile, o.pdlThicknessMm);
    for (const auto& [unn, p] : o.toothPdl) {
        const auto r = thicknessRangeMm(p, p.midRoot);
        range = {std::min(range.first, r.first), std::max(range.second, r.second)};
    }
    return range;
}

struct CarveRules {
    double voxel = 0.05;
    double ratio = 0.5;
    double uniformThickness = 0.2;      ///< the jaw's PDL (ToothWork holds each tooth's)
    std::optional<PdlProfile> profile;
    double maxThickness = 0.2;          ///< thickest PDL on any tooth (bands, reach)
    double gapBridge = 0.5;
    double boneShiftMax = 0.2;
    double apexTaper = 1.0;
    double clearance = 0.05;
    double far = 0.7;     ///< distances beyond the gap-bridging reach are reported as this (mm)
    double facingCos = 0.70710678118654752;  ///< -cos of CarveOptions::gapFacingDeg
    double minCapRise = 0;                   ///< CarveOptions::minCapRiseMm
    bool pdlKept = false;                    ///< CarveOptions::pdlKept
    double rootFacingCos = 0.70710678118654752;  ///< -cos of kKeptPdlRootFacingDeg (kept PDL, below the crest band)
};

/// Per-tooth working data.
struct ToothWork {
    int unn = 0;
    Label toothL = 0, pdlL = 0;
    bool implant = false;    ///< CarveOptions::implants: thickness 0, no PDL grid
    FloatGrid::ConstPtr T;   ///< tooth distance: input band, plus exterior distances where bone is
                             ///< within gap-bridging reach; +-far elsewhere outside the band
    FloatGrid::Ptr X;        ///< bone distance off the bone band where this tooth is within reach:
                             ///< outside (gaps) and inside down to boneShiftMax (overlaps)
    CoordBBox box;           ///< index bounds of T's active voxels
    double uniformThickness = 0.2;      ///< this tooth's PDL: the jaw's, or CarveOptions::toothPdl's
    std::optional<PdlProfile> profile;  ///< (uniformThickness is then the profile's mid-root value)
    bool hasRoot = false;    ///< axis, cervical and apical heights found (fitRootAxis)
    Vec3d origin{0, 0, 0}, axis{0, 0, 1};  ///< axis points from the root to the crown
    double hCervical = 0, hApex = 0;
};

/// Height of a world point along the tooth's long axis (mm; the crown is up).
inline double heightOf(const ToothWork& t, const Vec3d& world) { return (world - t.origin).dot(t.axis); }

/// PDL thickness at height h (heightOf) on the tooth's axis.
inline double thicknessAt(const ToothWork& t, double h) {
    if (!t.profile || !t.hasRoot) return t.uniformThickness;
    const double s = (t.hCervical - h) / std::max(t.hCervical - t.hApex, 1e-6);
    return pdlThicknessAt(*t.profile, s);
}

/// Share of the root erosion applied at a point: 1 except over the last apexTaper mm to the apex,
/// where it falls linearly to kApexErosionShare. Eroding a pointed apex by e pulls the tip back by
/// e / sin(half angle), more than e (0.178 mm for e = 0.1 on the shared mandible's tooth 22); the
/// socket side takes the rest of the thickness. Half, not none: the bone at the apex then moves
/// 0.15 mm rather than 0.2, which leaves room for the input's overlaps within #5's 0.25 mm.
constexpr double kApexErosionShare = 0.5;

/// Thinnest PDL an overlap of root and bone may leave, as a share of the thickness t (evalLocal).
constexpr double kMinPdlShare = 0.5;

inline double erosionShare(const ToothWork& t, const CarveRules& rules, double h) {
    if (!t.hasRoot || rules.apexTaper <= 0) return 1.0;
    const double s = std::clamp((h - t.hApex) / rules.apexTaper, 0.0, 1.0);
    return kApexErosionShare + (1.0 - kApexErosionShare) * s;
}

/// Signed bone distance: the tooth's extension X (exterior voxels within reach), else the input
/// band (active voxels are exact even at |value| = background), else "far" outside and the
/// clamped value inside (deep bone is in the socket anyway).
inline double signedBone(FloatAcc& B, FloatAcc& X, const CarveRules& rules, const Coord& c) {
    float v;
    if (X.probeValue(c, v)) return v;
    if (B.probeValue(c, v)) return v;  // band: exact, even at |v| = background
    return v > 0 ? rules.far : v;
}

/// Whether signedBone is a distance at c (X or the band), not a clamp without a direction.
inline bool boneKnown(FloatAcc& B, FloatAcc& X, const Coord& c) { return X.isValueOn(c) || B.isValueOn(c); }

/// The next double below x: turns "x <= 0" into the strict test "below(x) < 0".
inline double below(double x) { return std::nextafter(x, -std::numeric_limits<double>::infinity()); }

/// Tooth t's working fields (ToothWork::T, X, box) and its root axis: the tooth band used as
/// given (re-normalised only when narrower than the PDL rules need), tooth and bone distances
/// extended where a root-socket gap can be bridged or root and bone overlap.
void prepareTooth(ToothWork& t, const FloatGrid& tooth, const FloatGrid& bone, const CarveRules& rules, double exVoxels,
                  double inVoxels, const CarveOptions& options);

}  // namespace jawmesh::carve
