// Implements levelset/LowerCrest.h; what it computes, its rules and its contract are documented there.
#include "levelset/LowerCrest.h"

#include "io/Error.h"
#include "levelset/AlveolarCrest.h"
#include "levelset/Csg.h"
#include "levelset/RewriteLevelSet.h"

#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/Morphology.h>

#include <algorithm>
#include <limits>
#include <sstream>

namespace jawmesh {
namespace {

/// How far a point is from a root near the crest: its distance from the axis less the root's reach
/// in that direction (AlveolarCrest.h rootRadiusMm).
struct Footprint {
    const LongAxis* axis = nullptr;
    std::vector<double> radiusMm;
    double distanceOf(const openvdb::Vec3d& x) const {
        return axis->lateralOf(x) - radiusMm[std::size_t(axis->sectorOf(x, kCrestBins))];
    }
};

/// A listed tooth as the loss sees it.
struct Listed {
    Footprint root;
    const LongAxis* axis = nullptr;
    double floorMm = 0;          ///< nothing moves below this height
    double fillTopMm = 0;        ///< the socket fill ends at the old crest's lowest point
    openvdb::FloatGrid::Ptr tooth;  ///< its distance out past the gap: the socket fill is {T < gap}
};

/// Where and how far the bone drops.
struct LossZone {
    std::vector<Listed> listed;
    std::vector<Footprint> others;
    double depthMm = 0, rampMm = 0, gapMm = 0;

    /// The nearest listed root to x and the lateral share of the depth.
    std::pair<const Listed*, double> lateral(const openvdb::Vec3d& x) const {
        double nearL = std::numeric_limits<double>::infinity(), nearU = nearL;
        const Listed* n = nullptr;
        for (const Listed& l : listed)
            if (const double r = l.root.distanceOf(x); r < nearL) nearL = r, n = &l;
        for (const Footprint& o : others) nearU = std::min(nearU, o.distanceOf(x));
        const double towardsOthers = std::clamp(1.0 - (nearL - nearU) / kLossTaperMm, 0.0, 1.0);
        const double reach = std::clamp((kLossReachMm - nearL) / kLossTaperMm, 0.0, 1.0);
        return {n, towardsOthers * reach};
    }
    /// The depth (mm) by which the bone drops at x: the lateral share, ramped above the floor.
    std::pair<const Listed*, double> dropAt(const openvdb::Vec3d& x) const {
        const auto [n, share] = lateral(x);
        if (!n || share <= 0) return {n, 0.0};
        const double ramp = std::clamp((n->axis->heightOf(x) - n->floorMm) / rampMm, 0.0, 1.0);
        return {n, depthMm * share * ramp};
    }
    /// Where the bone at source p lands: x = p - drop(x) a, solved along the ramp (linear there).
    openvdb::Vec3d landing(const openvdb::Vec3d& p) const {
        const auto [n, share] = lateral(p);  // unchanged along the axis
        if (!n || share <= 0) return p;
        const double D = depthMm * share, hp = n->axis->heightOf(p) - n->floorMm;
        const double hx = hp - D >= rampMm ? hp - D : std::max(0.0, hp / (1.0 + D / rampMm));
        return p - n->axis->axis * (hp - hx);
    }
};

/// The bone with the listed sockets filled below their old crests, at a world point (mm).
float filledBone(const openvdb::FloatGrid& bone, const LossZone& zone, const openvdb::Vec3d& world) {
    const auto& xf = bone.transform();
    double b = openvdb::tools::BoxSampler::sample(bone.tree(), xf.worldToIndex(world));
    for (const Listed& l : zone.listed) {
        const double g = openvdb::tools::BoxSampler::sample(l.tooth->tree(), xf.worldToIndex(world)) - zone.gapMm;
        b = std::min(b, std::max(g, l.axis->heightOf(world) - l.fillTopMm));
    }
    return float(b);
}

}  // namespace

openvdb::FloatGrid::Ptr lowerCrest(const openvdb::FloatGrid& bone, const std::map<int, openvdb::FloatGrid::ConstPtr>& teeth,
                                   const std::map<int, LongAxis>& axes, const std::vector<int>& listed, double depthMm,
                                   double gapMm, std::vector<CrestLoss>& losses, const std::string& what) {
    LossZone zone;
    zone.depthMm = depthMm;
    zone.rampMm = kLossRampDepths * depthMm;
    zone.gapMm = gapMm;
    const double reachMm = gapMm + 2 * bandHalfWidthMm(bone);
    losses.clear();
    for (int unn : listed) {
        const LongAxis& axis = axes.at(unn);
        const CrestProfile crest = crestAround(bone, *teeth.at(unn), axis, what + ": tooth " + std::to_string(unn));
        const double floor = crest.minMm - depthMm - zone.rampMm;
        if (floor < crest.apexMm + kLossMinRootInBoneMm) {
            std::ostringstream s;
            s << what << ": tooth " << unn << "'s root reaches " << crest.minMm - crest.apexMm
              << " mm below its crest; a loss of " << depthMm << " mm (tapering over " << zone.rampMm
              << " mm below it) would leave its apex without bone";
            throw Error(s.str());
        }
        losses.push_back({unn, axis, crest.meanMm, 0, floor});
        zone.listed.push_back({{&axis, crest.rootRadiusMm}, &axis, floor, crest.minMm, withExteriorReach(*teeth.at(unn), reachMm)});
    }
    for (const auto& [unn, axis] : axes) {
        if (std::find(listed.begin(), listed.end(), unn) != listed.end()) continue;
        try {
            zone.others.push_back({&axis, crestAround(bone, *teeth.at(unn), axis, what).rootRadiusMm});
        } catch (const Error&) {
            // a tooth without bone around it has no crest to keep
        }
    }

    // Voxels whose value can change: the band where the bone drops, and where that band lands.
    const auto& xf = bone.transform();
    openvdb::MaskTree where(false);
    for (auto it = bone.tree().cbeginValueOn(); it; ++it) {
        const openvdb::Vec3d p = xf.indexToWorld(it.getCoord());
        if (zone.dropAt(p).second <= 0) continue;
        where.setValueOn(it.getCoord());
        where.setValueOn(openvdb::Coord::round(xf.worldToIndex(zone.landing(p))));
    }
    openvdb::tools::dilateActiveValues(where, 1, openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::IGNORE_TILES);
    auto lowered = rewriteLevelSet(bone, where, [&](const openvdb::Coord& ijk) {
        const float here = bone.tree().getValue(ijk);
        const openvdb::Vec3d x = xf.indexToWorld(ijk);
        const auto [n, drop] = zone.dropAt(x);
        if (drop <= 0) return here;
        return std::max(here, filledBone(bone, zone, x + n->axis->axis * drop));
    });
    for (CrestLoss& loss : losses)
        loss.crestAfterMm = crestAround(*lowered, *teeth.at(loss.unn), loss.axis, what).meanMm;
    return lowered;
}

}  // namespace jawmesh
