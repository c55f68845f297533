// Gap carving for one jaw, all teeth at once: bone and tooth level sets in, the labelled field of
// bone, teeth and periodontal ligaments (PDL) out (levelset/LabelField.h).
//
// Rules (per tooth i; T = tooth distance, B = bone distance, mm, negative inside; t = PDL thickness
// at the point, e = ratio * t root erosion, w = t - e socket widening):
//  * Socket. A point is "in the socket" of tooth i when bone is within e (B < e) or when it lies in
//    a thin gap that the segmentation left between root and socket: T + B < gapBridge with the
//    tooth and bone surfaces facing each other (grad T . grad B < cos gapFacingDeg, 135 degrees by
//    default). For two parallel surfaces a distance g apart, T + B = g at every point between and
//    inside, so the test bridges gaps up to gapBridge (default 0.5 mm; the real data has up to
//    0.45 mm at the cervical rim) without touching the crown above a crest where bone turns away
//    at more than 180 - gapFacingDeg degrees.
//    Wide gaps: where T + B = g exceeds w + boneShiftMax (default 0.2 mm), the PDL moves out to
//    w = g - boneShiftMax and e = max(0, t - w): the bone surface moves at most boneShiftMax,
//    the root is eroded less, and only past g = t + boneShiftMax does the PDL get thicker than t.
//  * Overlaps: where the root overlaps the bone (T + B = g < 0, facing), the bone surface would
//    move w - g. Past boneShiftMax the PDL's outer face stops at B = -boneShiftMax
//    (w = g + boneShiftMax) and the PDL is thinner than t there, down to t / 2; the root keeps
//    its erosion e, so neither surface moves more than the segmentation's overlap asks. (Bone
//    distances are extended boneShiftMax + 3 voxels into the bone near each root: an overlap
//    deeper than that, or a root buried with no bone surface facing it, keeps the rules above.)
//  * Apex: e falls linearly to e / 2 over the last apexTaper mm (default 1) of the root along the
//    tooth's long axis (w = t - e takes the rest), so a pointed apex is pulled back by no more
//    than about e (erosion moves a tip of half angle a by e / sin a).
//  * Tooth i keeps T <= -e, and T <= 0 outside the socket: only the root is eroded, the crown keeps
//    its input shape exactly.
//  * PDL i = {-e < T < w} inside the socket. Its top (the cap) is therefore the surface {B = e},
//    an offset of the bone surface: smooth, no steps, nothing to tune per tooth.
//  * Bone = (bone ∪ bridged gaps) outside {T_j < w} for every tooth j: teeth win overlaps, bone
//    and tooth meet only through the PDL, and the PDL stays t thick where the gap is wider than w
//    (the rest of the gap becomes bone, so there is no void between PDL and socket).
//  * Clearance: tooth i and its PDL keep only points where T_i - T_j < -clearance for every other
//    tooth j (split on the bisector); a final discrete pass removes the rare 26-neighbour contacts
//    left on diagonals.
// The distance grid of every region is the corresponding min/max combination of the input fields
// (exact zero set, true distance away from the creases), so it is consistent with the labels.
//
// Where the rules live (CarveGaps.cpp): socket, overlaps, apex, tooth and PDL at one voxel for one
// tooth in evalLocal; the bisector clearance in bisector. carveJaw runs six phases over one
// CarveContext: prepareTeeth (bands, gap-bridging extensions, root axis), labelVoxelsNearTeeth,
// assembleLabels, enforceClearance (the discrete pass), regionDistances, measureTeeth.
#pragma once

#include "io/Case.h"
#include "io/Labels.h"
#include "io/Progress.h"
#include "io/ToothAxes.h"
#include "levelset/LabelField.h"

#include <nlohmann/json.hpp>
#include <openvdb/openvdb.h>

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace jawmesh {

/// PDL thickness along the root: linear from the cervical end (at the alveolar crest) to mid-root
/// and from mid-root to the apex, measured along the tooth's long axis. mm.
struct PdlProfile {
    double cervical = 0.2, midRoot = 0.2, apical = 0.2;
};

struct CarveOptions {
    double pdlThicknessMm = 0.2;        ///< uniform PDL thickness (ignored when profile is set)
    double pdlRatio = 0.5;              ///< share of the thickness taken from the root (erosion), [0, 1]
    std::optional<PdlProfile> profile;  ///< thickness along the root instead of a uniform value
    double clearanceVoxels = 1.0;       ///< gap between different teeth / PDLs, voxels
    double gapBridgeMm = 0.5;           ///< widest root-socket gap bridged (see file comment)
    double boneShiftMaxMm = 0.2;        ///< farthest a bridged gap or an overlap moves the bone surface (file comment)
    double gapFacingDeg = 135;          ///< a gap is bridged where tooth and bone normals make more than this angle
    double minCapRiseMm = 0;            ///< the PDL's cap {B = e} rises at least this far above the bone (kept PDL: e = 0)
    double apexTaperMm = 1.0;           ///< root erosion falls to half over this length to the apex; 0 = off
    double capExclusionMm = 0.3;        ///< thickness statistics ignore points this close to the outside
    std::map<int, PdlProfile> toothPdl; ///< a tooth's own PDL (UNN -> profile; uniform: three equal values)
    std::map<int, ToothAxes> axes;      ///< optional tooth axes (long axis for the profile)
    bool pdlKept = false;               ///< set by keptPdlCarveOptions (recorded in summary.json)
    /// UNNs whose level set is an implant (an edit, levelset/ImplantBody.h): carved as a tooth with
    /// no PDL (thickness 0: no erosion, no widening, its gaps bridged into bone), so it is fused
    /// to the bone; labelled implantLabel(unn).
    std::set<int> implants;
};

struct ThicknessStats {
    std::size_t samples = 0;
    double min = 0, p05 = 0, mean = 0, p95 = 0, max = 0;  ///< mm
};

struct ToothCarveSummary {
    int unn = 0;
    double toothVolumeMm3 = 0;   ///< carved tooth
    double pdlVolumeMm3 = 0;
    double rootAreaFraction = 0; ///< root/crown split: share of the carved tooth's surface facing its PDL
    bool impacted = false;       ///< PDL forms a closed envelope (no PDL face to the outside)
    bool implant = false;        ///< an implant (CarveOptions::implants): no PDL by design
    ThicknessStats thickness;    ///< tooth-side PDL interface to bone-side interface, cap excluded
};

/// Wall time and process peak resident memory at the end of one carving stage.
struct CarveStageTiming {
    std::string name;
    double seconds = 0;
    std::uint64_t peakMemoryBytes = 0;
};

struct CarveSummary {
    double voxelSizeMm = 0;
    std::vector<ToothCarveSummary> teeth;
    std::size_t clearanceVoxelsRemoved = 0;  ///< voxels dropped by the discrete 26-neighbour pass
    std::size_t toothBoneContacts = 0;       ///< tooth voxels 26-adjacent to bone (should be 0)
    std::vector<std::string> warnings;
    double seconds = 0;
    std::vector<CarveStageTiming> stages;    ///< in order: tooth bands, labels, assembly, clearance, ...
};

/// Carves the PDL of every tooth and labels the jaw (see the file comment for the rules).
/// @param jaw      which bone label to use
/// @param bone     bone level set (band >= 2 voxels: gap bridging starts from its inner layers; it
///                 is extended beyond its band only near the teeth, where a gap can be bridged)
/// @param teeth    UNN -> tooth level set; all grids on one transform (meshToLevelSet with one
///                 voxel size); not modified
/// @param options  thickness, ratio, profile, clearance (CarveOptions)
/// @param summary  filled: per-tooth volumes, thickness statistics, warnings (e.g. a tooth without
///                 bone contact gets no PDL)
/// @throws Error for mismatched transforms, invalid UNNs or options, a voxel too coarse for the PDL
///         (fewer than 2 voxels across); Cancelled when progress is cancelled.
/// Deterministic regardless of the thread count. Cost: per tooth (teeth in parallel) a dilation of
/// its band and a closest-point propagation of tooth and bone distances into the few voxels where a
/// root-socket gap can be bridged (no re-meshing unless the input band is narrower than the PDL
/// needs), then passes over the tooth bands (TBB); memory of the order of the bone grid plus the
/// tooth bands.
LabelField carveJaw(Jaw jaw, const openvdb::FloatGrid& bone,
                    const std::map<int, openvdb::FloatGrid::ConstPtr>& teeth, const CarveOptions& options,
                    CarveSummary& summary, Progress& progress = noProgress());

/// Thinnest kept PDL, in voxels of the carve's grid (keptPdlCarveOptions).
constexpr double kKeptPdlMinVoxels = 2.0;
/// Widest root-socket gap a kept PDL fills, mm: segmented PDLs are 0.1-0.5 mm thick.
constexpr double kKeptPdlBridgeMm = 0.8;
/// Facing angle of a kept PDL's gap: above the bone's rim the gap bridge grows a wedge of PDL up
/// the crown, as high as the gap is wide times tan(180 - angle). At 135 degrees the 0.1 mm
/// 14-tooth phantom kept 131 tets under 10 degrees (the improver ran 12 minutes); at 160, 7.
constexpr double kKeptPdlFacingDeg = 160;
/// ... but only within kKeptPdlCrestBandMm below the cervical height (along the tooth's axis):
/// deeper there is no crown for the bridge to climb, and gaps whose walls meet at 135-160 degrees
/// (round apices, flaring sockets) left 2 % of the 14-tooth phantom's PDL voxels outside the PDL,
/// as pockets the label clean-up then filled with bone. There the generated PDL's angle applies.
constexpr double kKeptPdlCrestBandMm = 1.0;
constexpr double kKeptPdlRootFacingDeg = 135;

/// The options that keep a segmented PDL (JawSurfaces::pdlKept: the bone leaves it out, so it is
/// the gap between root and socket): the rules above with no root erosion (ratio 0) and no bone
/// shift, so the PDL is the gap as segmented, bridged up to the wider of options.gapBridgeMm and
/// kKeptPdlBridgeMm where the surfaces face each other past kKeptPdlFacingDeg; where the gap is
/// thinner than kKeptPdlMinVoxels voxels (or missing: root and bone in contact) the bone gives way
/// until the PDL is that thick, and the cap rises that far above the bone. Thickness and profile
/// of `options` are replaced; the rest (clearance, axes, cap exclusion) is kept.
CarveOptions keptPdlCarveOptions(CarveOptions options, double voxelMm);

/// The carve's options for a jaw: `options` with the jaw's axes when it gives none, turned into
/// keptPdlCarveOptions when the jaw's label map keeps its PDL.
CarveOptions carveOptionsFor(const JawSurfaces& surfaces, CarveOptions options, double voxelMm);

/// Band half width (voxels of `voxelMm`) the tooth level sets need for carving to take them as
/// they are: the erosion inside, the socket widening plus the clearance outside, for the thickest
/// PDL of the jaw (CarveOptions::toothPdl included). A narrower band is rebuilt per tooth with
/// OpenVDB's levelSetRebuild, which took 102 of the 14-tooth phantom's kept-PDL carve's 106 s
/// (its PDL rules need 5 voxels against the level sets' 3).
double toothBandVoxels(const CarveOptions& options, double voxelMm);

/// PDL thickness (mm) at relative root position s (0 cervical, 0.5 mid-root, 1 apex), clamped.
double pdlThicknessAt(const PdlProfile& profile, double s);

/// The options as summary.json records them (mm, voxels).
nlohmann::json toJson(const CarveOptions& options);

/// The options back from toJson's form (axes are not part of it). Throws Error naming `name`
/// for a missing key or a wrong value type.
CarveOptions carveOptionsFromJson(const nlohmann::json& j, const std::string& name);

/// Per-tooth measurements (volumes mm^3, thickness statistics mm), clearance, contacts, warnings
/// and carve_seconds, as summary.json records them.
nlohmann::json toJson(const CarveSummary& summary);

/// Throws Error naming the tooth's file when a carved tooth (not an implant) got no PDL: it does not reach the bone
/// (a tooth in another coordinate frame, of the other jaw, or far from its socket). runJaw calls it
/// after carving, before the long surface and TetGen stages that would end in a missing PDL.
void requireBoneContact(const CarveSummary& summary, const JawCase& jawCase, const CarveOptions& options);

}  // namespace jawmesh
