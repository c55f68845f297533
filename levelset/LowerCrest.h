// Horizontal bone loss (issue #24): the alveolar crest around chosen teeth lowered by a depth d
// along each tooth's long axis a. The bone is intersected with a copy of itself moved down by the
// depth, B'(x) = max(B(x), F(x + s(x))) (outside both, the distance to their crossing edge): every
// upward-facing part of the crest drops by d exactly and walls along the axis stay. F is the bone
// with each listed tooth's socket filled (the tooth dilated by the widest gap carving bridges,
// below the lowest point of its old crest), so the socket's walls and floor, which face up where a
// root tapers, do not widen or deepen. The shift s(x) = d w a, along the axis of the nearest listed
// root, tapers w to none: towards the teeth that are not listed, from full where x is as near a
// listed root as an unlisted one to none kLossTaperMm nearer the unlisted one (the whole crest
// around every listed tooth drops by d; the slope lies in the septum beside it); beyond
// kLossReachMm from the listed roots; and downwards over kLossRampDepths * d (less on a short root)
// to a floor under which nothing moves (other upward-facing bone, e.g. a lingual ridge, drops by
// less the deeper it is). Distances to a root are taken from its axis less its radius at the crest
// in that direction (AlveolarCrest.h). The carve that follows caps each PDL at the new crest.
#pragma once

#include "levelset/ToothLongAxis.h"

#include <openvdb/openvdb.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace jawmesh {

/// Width of the slope at the lateral edges of a bone loss, mm.
constexpr double kLossTaperMm = 1.5;
/// Distance from a listed root beyond which no bone is lost, mm (full loss up to kLossReachMm -
/// kLossTaperMm: past the widest alveolar ridge around a molar).
constexpr double kLossReachMm = 7.0;
/// The depth ramps from full at the new crest's lowest point to none over this many depths (less
/// on a short root, down to kLossMinRampMm).
constexpr double kLossRampDepths = 2.0;
constexpr double kLossMinRampMm = 0.5;
/// A root must keep this much bone between the floor and its apex, mm.
constexpr double kLossMinRootInBoneMm = 1.0;

/// One listed tooth: crest heights along its axis (AlveolarCrest.h mean of the bins) and the floor.
struct CrestLoss {
    int unn = 0;
    LongAxis axis;
    double crestBeforeMm = 0, crestAfterMm = 0, floorMm = 0;
    double sideDropMm = 0;  ///< an angular defect: the crest's drop in the sector of its side
};

/// Where the loss applies around a listed root: all around (horizontal), or as an angular
/// (vertical) defect on one side: the full depth at the root in direction `side` (a unit vector
/// across the axis), falling to none `widthMm` out from the root and 60 degrees around it.
struct LossShape {
    std::optional<openvdb::Vec3d> side;
    double widthMm = 0;
};

/// The bone with its crest lowered by depthMm around the teeth `listed` (UNNs of `teeth`). `axes`
/// holds every tooth's axis (listed or not: the others bound the loss); gapMm is the socket fill's
/// dilation (CarveOptions::gapBridgeMm). Fills `losses`, one per listed tooth. Throws
/// Error("<what>: ...") when a listed tooth has no crest (no bone near it) or the loss would leave
/// less than kLossMinRootInBoneMm + kLossMinRampMm of its root in bone.
/// Cost: a closest-point propagation around each listed tooth (in parallel), every bone voxel of
/// the zone evaluated in parallel (17 s for four incisors of the shared mandible).
openvdb::FloatGrid::Ptr lowerCrest(const openvdb::FloatGrid& bone, const std::map<int, openvdb::FloatGrid::ConstPtr>& teeth,
                                   const std::map<int, LongAxis>& axes, const std::vector<int>& listed, double depthMm,
                                   double gapMm, std::vector<CrestLoss>& losses, const std::string& what,
                                   const LossShape& shape = {});

}  // namespace jawmesh
