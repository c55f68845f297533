// Implements levelset/LowerCrest.h; what it computes, its rules and its contract are documented there.
#include "levelset/LowerCrest.h"

#include "io/Error.h"
#include "levelset/AlveolarCrest.h"
#include "levelset/Csg.h"
#include "levelset/RewriteLevelSet.h"

#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

namespace jawmesh {
namespace {

/// How far a point is from a root near the crest: its distance from the axis less the root's reach
/// in that direction (AlveolarCrest.h rootRadiusMm).
struct Footprint {
    const LongAxis* axis = nullptr;
    std::vector<double> radiusMm;
    double widestMm = 0;  ///< the largest of radiusMm
    Footprint(const LongAxis* a, std::vector<double> radius) : axis(a), radiusMm(std::move(radius)) {
        for (double r : radiusMm) widestMm = std::max(widestMm, r);
    }
    /// The distance from x, or `limit` when it cannot be less (skips the sector's angle).
    double distanceOf(const openvdb::Vec3d& x, double limit = std::numeric_limits<double>::infinity()) const {
        const double lateral = axis->lateralOf(x);
        if (lateral - widestMm >= limit) return limit;
        return lateral - radiusMm[std::size_t(axis->sectorOf(x, kCrestBins))];
    }
};

/// A listed tooth as the loss sees it.
struct Listed {
    Footprint root{nullptr, {}};
    const LongAxis* axis = nullptr;
    double floorMm = 0;          ///< nothing moves below this height
    double fillTopMm = 0;        ///< the socket fill ends at the old crest's lowest point
    openvdb::FloatGrid::Ptr tooth;  ///< its distance out past the gap: the socket fill is {T < gap}
    double crestTopMm = 0;          ///< the old crest's highest sector
    double rampMm = 0;              ///< the depth falls to none over this far below the new crest
};

/// Where and how far the bone drops.
struct LossZone {
    std::vector<Listed> listed;
    std::vector<Footprint> others;
    LossShape shape;
    double depthMm = 0, gapMm = 0;

    /// Share of the depth at x around the listed root n for an angular defect: full at the root
    /// towards the side, none the defect's width out or 60 degrees around.
    double defectShare(const Listed& n, double fromRoot, const openvdb::Vec3d& x) const {
        openvdb::Vec3d across = x - n.axis->origin;
        across -= n.axis->axis * across.dot(n.axis->axis);
        const double c = across.length() > 1e-9 ? across.unit().dot(*shape.side) : 1.0;
        return std::clamp(1.0 - fromRoot / shape.widthMm, 0.0, 1.0) * std::clamp((c - 0.5) / 0.5, 0.0, 1.0);
    }

    /// The nearest listed root to x and the lateral share of the depth.
    std::pair<const Listed*, double> lateral(const openvdb::Vec3d& x) const {
        double nearL = std::numeric_limits<double>::infinity(), nearU = nearL;
        const Listed* n = nullptr;
        for (const Listed& l : listed)
            if (const double r = l.root.distanceOf(x, nearL); r < nearL) nearL = r, n = &l;
        // An unlisted root no nearer than the nearest listed one leaves the depth whole.
        for (const Footprint& o : others) nearU = std::min(nearU, o.distanceOf(x, std::min(nearU, nearL)));
        const double towardsOthers = std::clamp(1.0 - (nearL - nearU) / kLossTaperMm, 0.0, 1.0);
        if (n && shape.side) return {n, towardsOthers * defectShare(*n, std::max(nearL, 0.0), x)};
        const double reach = std::clamp((kLossReachMm - nearL) / kLossTaperMm, 0.0, 1.0);
        return {n, towardsOthers * reach};
    }
    /// The depth (mm) by which the bone drops at x: the lateral share, ramped above the floor.
    std::pair<const Listed*, double> dropAt(const openvdb::Vec3d& x) const {
        const auto [n, share] = lateral(x);
        if (!n || share <= 0) return {n, 0.0};
        const double ramp = std::clamp((n->axis->heightOf(x) - n->floorMm) / n->rampMm, 0.0, 1.0);
        return {n, depthMm * share * ramp};
    }
};

/// The bone with the listed sockets filled below their old crests, read through one thread's
/// accessors at a world point (mm).
struct FilledBone {
    const openvdb::FloatGrid& bone;
    const LossZone& zone;
    openvdb::FloatGrid::ConstAccessor boneAcc;
    std::vector<openvdb::FloatGrid::ConstAccessor> toothAcc;

    FilledBone(const openvdb::FloatGrid& b, const LossZone& z) : bone(b), zone(z), boneAcc(b.getConstAccessor()) {
        for (const Listed& l : z.listed) toothAcc.push_back(l.tooth->getConstAccessor());
    }
    float operator()(const openvdb::Vec3d& world) {
        const openvdb::Vec3d ijk = bone.transform().worldToIndex(world);
        double b = openvdb::tools::BoxSampler::sample(boneAcc, ijk);
        for (std::size_t i = 0; i < zone.listed.size(); ++i) {
            const Listed& l = zone.listed[i];
            const double g = openvdb::tools::BoxSampler::sample(toothAcc[i], ijk) - zone.gapMm;
            b = std::min(b, std::max(g, l.axis->heightOf(world) - l.fillTopMm));
        }
        return float(b);
    }
};

/// a ∩ b (signed distances, mm) with its outside rounded: where both are outside, the distance to
/// the edge where they cross as if it were a right angle, sqrt(a² + b²), not max(a, b). At the new
/// crest's rim (the socket wall under the cut top) max's square contours turn the gradient by 90°
/// across one voxel on the bisector, and the carve's facing test flipped there voxel by voxel into a
/// checkerboard of PDL on the root (BENCHMARKS session 27). Where either is inside, max(a, b): the
/// zero set, so the bone itself, is the same.
float roundedIntersection(float a, float b) {
    if (a > 0 && b > 0) return std::sqrt(a * a + b * b);
    return std::max(a, b);
}

/// Index box around a listed tooth holding every voxel its loss can change: the axis from the
/// floor to well over the old crest's top near the root (bone farther out, a lingual plate, may
/// rise higher), widened by the loss's reach and the root's radius.
openvdb::CoordBBox lossBox(const Listed& l, double crestTopMm, double reachMm, double depthMm,
                           const openvdb::math::Transform& xf) {
    double radius = 0;
    for (double r : l.root.radiusMm) radius = std::max(radius, r);
    radius += reachMm;
    openvdb::BBoxd box;
    for (double h : {l.floorMm, crestTopMm + depthMm + kLossReachMm}) {
        const openvdb::Vec3d c = xf.worldToIndex(l.axis->origin + l.axis->axis * h);
        box.expand(c - openvdb::Vec3d(radius / xf.voxelSize()[0]));
        box.expand(c + openvdb::Vec3d(radius / xf.voxelSize()[0]));
    }
    return openvdb::CoordBBox(openvdb::Coord::floor(box.min()), openvdb::Coord::ceil(box.max()));
}

}  // namespace

openvdb::FloatGrid::Ptr lowerCrest(const openvdb::FloatGrid& bone, const std::map<int, openvdb::FloatGrid::ConstPtr>& teeth,
                                   const std::map<int, LongAxis>& axes, const std::vector<int>& listed, double depthMm,
                                   double gapMm, std::vector<CrestLoss>& losses, const std::string& what,
                                   const LossShape& shape) {
    LossZone zone;
    zone.shape = shape;
    const double lossReach = shape.side ? shape.widthMm : kLossReachMm;
    zone.depthMm = depthMm;
    zone.gapMm = gapMm;
    const double reachMm = gapMm + 2 * bandHalfWidthMm(bone);
    losses.clear();
    std::vector<CrestProfile> crests;  // before the loss, one per listed tooth
    for (int unn : listed) {
        const LongAxis& axis = axes.at(unn);
        const CrestProfile crest = crestAround(bone, *teeth.at(unn), axis, what + ": tooth " + std::to_string(unn));
        // The ramp is kLossRampDepths depths long, shorter on a short root, never under kLossMinRampMm.
        const double room = crest.minMm - depthMm - (crest.apexMm + kLossMinRootInBoneMm);
        const double ramp = std::min(kLossRampDepths * depthMm, room);
        if (ramp < kLossMinRampMm) {
            std::ostringstream s;
            s << what << ": tooth " << unn << "'s root reaches " << crest.minMm - crest.apexMm << " mm below its crest; a loss of "
              << depthMm << " mm would leave less than " << kLossMinRootInBoneMm + kLossMinRampMm << " mm of it in bone";
            throw Error(s.str());
        }
        const double floor = crest.minMm - depthMm - ramp;
        losses.push_back({unn, axis, crest.meanMm, 0, floor});
        crests.push_back(crest);
        const double top = *std::max_element(crest.heightsMm.begin(), crest.heightsMm.end());
        zone.listed.push_back({{&axis, crest.rootRadiusMm}, &axis, floor, crest.minMm, nullptr, top, ramp});
    }
    // The socket fills (closest-point propagation, serial each): the listed teeth in parallel.
    tbb::parallel_for(std::size_t(0), listed.size(),
                      [&](std::size_t i) { zone.listed[i].tooth = withExteriorReach(*teeth.at(listed[i]), reachMm); });
    // The teeth that bound the loss: those within its reach (the others cannot be nearer).
    const auto& xf = bone.transform();
    std::vector<openvdb::CoordBBox> reach;
    for (const Listed& l : zone.listed) {
        reach.push_back(lossBox(l, l.crestTopMm, lossReach, depthMm, xf));
        reach.back().expand(int(std::ceil(kLossReachMm / xf.voxelSize()[0])));
    }
    for (const auto& [unn, axis] : axes) {
        if (std::find(listed.begin(), listed.end(), unn) != listed.end()) continue;
        const openvdb::CoordBBox box = teeth.at(unn)->evalActiveVoxelBoundingBox();
        if (std::none_of(reach.begin(), reach.end(), [&](const openvdb::CoordBBox& r) { return r.hasOverlap(box); })) continue;
        try {
            zone.others.push_back({&axis, crestAround(bone, *teeth.at(unn), axis, what).rootRadiusMm});
        } catch (const Error&) {
            // a tooth without bone around it has no crest to keep
        }
    }

    // Voxels whose value can change: bone (inside or in its band) near the listed crests.
    openvdb::MaskTree where(false);
    for (const Listed& l : zone.listed) where.fill(lossBox(l, l.crestTopMm, lossReach, depthMm, xf), true, true);
    openvdb::MaskTree boneOrBand(bone.tree(), false, openvdb::TopologyCopy());
    boneOrBand.topologyUnion(openvdb::tools::sdfInteriorMask(bone)->tree());
    where.topologyIntersection(boneOrBand);
    auto lowered = rewriteLevelSet(bone, std::move(where), [&]() -> VoxelValue {
        auto filled = std::make_shared<FilledBone>(bone, zone);
        return [&, filled](const openvdb::Coord& ijk) {
            const float here = filled->boneAcc.getValue(ijk);
            const openvdb::Vec3d x = xf.indexToWorld(ijk);
            const auto [n, drop] = zone.dropAt(x);
            if (drop <= 0) return here;
            return roundedIntersection(here, (*filled)(x + n->axis->axis * drop));
        };
    });
    for (std::size_t i = 0; i < losses.size(); ++i) {
        CrestLoss& loss = losses[i];
        const CrestProfile& before = crests[i];
        const CrestProfile after = crestAround(*lowered, *teeth.at(loss.unn), loss.axis, what);
        loss.crestAfterMm = after.meanMm;
        if (shape.side) {
            const int sector = loss.axis.sectorOf(loss.axis.origin + *shape.side, kCrestBins);
            loss.sideDropMm = before.sectorHeightsMm[std::size_t(sector)] - after.sectorHeightsMm[std::size_t(sector)];
        }
    }
    return lowered;
}

}  // namespace jawmesh
