// Implements levelset/JawEdits.h; what it computes, its rules and its contract are documented there.
#include "levelset/JawEdits.h"

#include "levelset/CarveRules.h"
#include "levelset/Csg.h"
#include "levelset/HealSocket.h"
#include "levelset/ImplantBody.h"
#include "levelset/LowerCrest.h"

#include <openvdb/tools/Interpolation.h>

#include <chrono>
#include <iomanip>
#include <sstream>
#include <type_traits>

namespace jawmesh {
namespace {

/// A tooth's surface touches the bone where the bone's band is under this, mm (ToothLongAxis.h).
constexpr double kAxisContactMm = 0.2;

nlohmann::json toJson(const LongAxis& a) {
    return {{"origin", {a.origin.x(), a.origin.y(), a.origin.z()}}, {"direction", {a.axis.x(), a.axis.y(), a.axis.z()}}};
}

struct EditContext {
    JawLevelSets& levelSets;
    CarveOptions& carve;
    std::string where;  ///< "<file>: edits[i]" for messages

    LongAxis axisOf(int unn) const {
        const auto given = carve.axes.find(unn);
        return toothLongAxis(*levelSets.teeth.at(unn), *levelSets.bone, kAxisContactMm,
                             given != carve.axes.end() ? &given->second : nullptr);
    }
    /// Every tooth's axis (a loss is bounded by the teeth it does not list).
    std::map<int, LongAxis> allAxes() const {
        std::map<int, LongAxis> axes;
        for (const auto& [unn, grid] : levelSets.teeth) axes[unn] = axisOf(unn);
        return axes;
    }
};

nlohmann::json apply(EditContext& ctx, const ExtractEdit& e) {
    nlohmann::json record = {{"op", "extract"}, {"tooth", e.tooth}, {"socket", e.healed ? "healed" : "empty"}};
    if (e.healed) {
        SocketFill fill;
        const LongAxis axis = ctx.axisOf(e.tooth);
        ctx.levelSets.bone = healSocket(*ctx.levelSets.bone, *ctx.levelSets.teeth.at(e.tooth), axis,
                                        ctx.carve.gapBridgeMm, fill, ctx.where);
        record["fill_level_mm"] = fill.levelMm;
        record["filled_volume_mm3"] = fill.filledVolumeMm3;
        record["axis"] = toJson(axis);
    }
    ctx.levelSets.teeth.erase(e.tooth);
    ctx.carve.toothPdl.erase(e.tooth);
    return record;
}

nlohmann::json apply(EditContext& ctx, const BoneLossEdit& e) {
    const std::map<int, LongAxis> axes = ctx.allAxes();
    std::vector<CrestLoss> losses;
    ctx.levelSets.bone = lowerCrest(*ctx.levelSets.bone, ctx.levelSets.teeth, axes, e.teeth, e.depthMm,
                                     ctx.carve.gapBridgeMm, losses, ctx.where);
    nlohmann::json teeth = nlohmann::json::array();
    for (const CrestLoss& l : losses)
        teeth.push_back({{"tooth", l.unn},
                         {"axis", toJson(l.axis)},
                         {"crest_before_mm", l.crestBeforeMm},
                         {"crest_after_mm", l.crestAfterMm},
                         {"crest_drop_mm", l.crestBeforeMm - l.crestAfterMm},
                         {"floor_mm", l.floorMm}});
    return {{"op", "bone_loss"}, {"depth_mm", e.depthMm}, {"teeth", teeth}};
}

/// Whether `unn`'s mesial neighbour has the next UNN (the jaw's left half: 1-8, 17-24).
bool mesialIsNext(int unn) { return (unn >= 1 && unn <= 8) || (unn >= 17 && unn <= 24); }

/// A unit vector across tooth `unn`'s axis towards `side`: mesial towards the neighbour nearer the
/// midline (or away from the other one), buccal away from the centre of the jaw's teeth.
openvdb::Vec3d sideDirection(int unn, AngularDefectEdit::Side side, const std::map<int, LongAxis>& axes,
                             const std::string& where) {
    const LongAxis& a = axes.at(unn);
    const auto across = [&](openvdb::Vec3d v) { return (v - a.axis * v.dot(a.axis)).unit(); };
    const int mesial = mesialIsNext(unn) ? unn + 1 : unn - 1, distal = mesialIsNext(unn) ? unn - 1 : unn + 1;
    openvdb::Vec3d toMesial;
    if (axes.count(mesial)) toMesial = across(axes.at(mesial).origin - a.origin);
    else if (axes.count(distal)) toMesial = across(a.origin - axes.at(distal).origin);
    else throw Error(where + ": tooth " + std::to_string(unn) + " has no neighbour to tell mesial from distal by");
    openvdb::Vec3d centre(0, 0, 0);
    for (const auto& [other, axis] : axes) centre += axis.origin;
    centre /= double(axes.size());
    openvdb::Vec3d buccal = a.axis.cross(toMesial).unit();
    if (buccal.dot(a.origin - centre) < 0) buccal = -buccal;
    switch (side) {
        case AngularDefectEdit::Side::Mesial: return toMesial;
        case AngularDefectEdit::Side::Distal: return -toMesial;
        case AngularDefectEdit::Side::Buccal: return buccal;
        case AngularDefectEdit::Side::Lingual: return -buccal;
    }
    return toMesial;
}

nlohmann::json apply(EditContext& ctx, const AngularDefectEdit& e) {
    const std::map<int, LongAxis> axes = ctx.allAxes();
    LossShape shape{sideDirection(e.tooth, e.side, axes, ctx.where), e.widthMm};
    std::vector<CrestLoss> losses;
    ctx.levelSets.bone = lowerCrest(*ctx.levelSets.bone, ctx.levelSets.teeth, axes, {e.tooth}, e.depthMm,
                                     ctx.carve.gapBridgeMm, losses, ctx.where, shape);
    const CrestLoss& l = losses.at(0);
    return {{"op", "bone_loss"},
            {"tooth", e.tooth},
            {"side", sideName(e.side)},
            {"side_direction", {shape.side->x(), shape.side->y(), shape.side->z()}},
            {"depth_mm", e.depthMm},
            {"width_mm", e.widthMm},
            {"axis", toJson(l.axis)},
            {"crest_drop_at_side_mm", l.sideDropMm},
            {"crest_drop_mean_mm", l.crestBeforeMm - l.crestAfterMm},
            {"floor_mm", l.floorMm}};
}

nlohmann::json apply(EditContext& ctx, const PdlThicknessEdit& e) {
    ctx.carve.toothPdl[e.tooth] = PdlProfile{e.cervicalMm, e.midRootMm, e.apicalMm};
    return {{"op", "pdl_thickness"},
            {"tooth", e.tooth},
            {"profile_mm", {{"cervical", e.cervicalMm}, {"mid_root", e.midRootMm}, {"apical", e.apicalMm}}}};
}

/// How far past the implant's tip the depth is measured, mm (run.json records the bone's depth up
/// to the body's length plus this).
constexpr double kBoneDepthBeyondTipMm = 5.0;

/// How deep the bone reaches below the platform along the axis and, from the body's length on,
/// over its apical disc's rim (mm, in steps of half a voxel, up to kBoneDepthBeyondTipMm past the
/// tip): an implant longer than that would leave the bone. Returns the first depth at which a
/// sample is outside the bone.
double boneDepthBelowPlatform(const openvdb::FloatGrid& bone, const ImplantEdit& e, const ImplantPlacement& at) {
    const openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler> B(
        bone.getConstAccessor(), bone.transform());
    const LongAxis& a = at.axis;
    const openvdb::Vec3d across = a.across();
    const openvdb::Vec3d across2 = a.axis.cross(across);
    const double r = 0.5 * e.diameterMm, step = 0.5 * uniformVoxelSizeMm(bone);
    // From two voxels down: a platform at the crest lies on the bone's surface.
    const double deepest = e.lengthMm + kBoneDepthBeyondTipMm;
    for (double depth = 4 * step; depth <= deepest; depth += step) {
        const openvdb::Vec3d c = a.origin + a.axis * (at.platformMm - depth);
        if (B.wsSample(c) >= 0) return depth;
        // The apical disc's rim: a body whose tip is in bone but whose side pokes out is too long too.
        if (depth >= e.lengthMm - step)
            for (int k = 0; k < 8; ++k) {
                const double phi = k * M_PI / 4;
                if (B.wsSample(c + (across * std::cos(phi) + across2 * std::sin(phi)) * r) >= 0) return depth;
            }
    }
    return deepest;
}

/// Throws Error when the implant's surface comes within a PDL and a voxel of another tooth (or
/// within that tooth's band, when it is narrower): it would cut into that root or its ligament
/// (carving would split them on the bisector instead).
void requireClearOfTeeth(const openvdb::FloatGrid& implant, int unn, const std::map<int, openvdb::FloatGrid::ConstPtr>& teeth,
                         double reachMm, const std::string& where) {
    for (const auto& [other, grid] : teeth) {
        if (other == unn) continue;
        auto T = grid->getConstAccessor();
        // Off its band a level set holds +-background: only a value under it is a distance.
        const double reach = std::min(reachMm, 0.99 * bandHalfWidthMm(*grid));
        for (auto v = implant.cbeginValueOn(); v; ++v)
            if (*v <= 0 && T.getValue(v.getCoord()) < reach)
                throw Error(where + ": the implant in place of tooth " + std::to_string(unn) + " reaches tooth " +
                            std::to_string(other) + " (its root or PDL); choose a narrower or shorter implant");
    }
}

nlohmann::json apply(EditContext& ctx, const ImplantEdit& e) {
    const LongAxis axis = ctx.axisOf(e.tooth);
    const openvdb::FloatGrid& tooth = *ctx.levelSets.teeth.at(e.tooth);
    SocketFill fill;
    auto healed = healSocket(*ctx.levelSets.bone, tooth, axis, ctx.carve.gapBridgeMm, fill, ctx.where);
    const ImplantPlacement at{axis, fill.levelMm - e.platformDepthMm, fill.levelMm};
    const double boneDepth = boneDepthBelowPlatform(*healed, e, at);
    if (boneDepth <= e.lengthMm) {
        std::ostringstream s;
        s << std::fixed << std::setprecision(1) << ctx.where << ": a " << e.lengthMm << " mm implant along tooth " << e.tooth
          << "'s axis leaves the bone " << boneDepth << " mm below its platform; choose a shorter implant";
        throw Error(s.str());
    }
    auto implant = implantLevelSet(e, at, tooth);
    const double pdlMax = carve::thicknessRangeMm(ctx.carve).second;
    requireClearOfTeeth(*implant, e.tooth, ctx.levelSets.teeth, pdlMax + uniformVoxelSizeMm(*implant), ctx.where);
    ctx.levelSets.bone = healed;
    ctx.levelSets.teeth[e.tooth] = implant;
    ctx.carve.toothPdl.erase(e.tooth);
    ctx.carve.implants.insert(e.tooth);
    const openvdb::Vec3d platform = axis.origin + axis.axis * at.platformMm;
    nlohmann::json record = toJson(e);
    record["axis"] = toJson(axis);
    record["platform_centre"] = {platform.x(), platform.y(), platform.z()};
    record["crest_mm"] = fill.levelMm;
    record["platform_mm"] = at.platformMm;
    record["bone_depth_below_platform_mm"] = boneDepth;
    record["body_volume_mm3"] = implantBodyVolumeMm3(e);
    record["filled_volume_mm3"] = fill.filledVolumeMm3;
    return record;
}

}  // namespace

nlohmann::json applyEdits(const EditList& edits, JawLevelSets& levelSets, CarveOptions& carve, Progress& progress) {
    std::vector<int> present;
    for (const auto& [unn, grid] : levelSets.teeth) present.push_back(unn);
    requireEditsFit(edits, present);
    nlohmann::json applied = nlohmann::json::array();
    ProgressStage stage(progress, "edits");
    for (std::size_t i = 0; i < edits.edits.size(); ++i) {
        progress.checkCancelled();
        EditContext ctx{levelSets, carve, edits.file + ": edits[" + std::to_string(i) + "]"};
        const auto start = std::chrono::steady_clock::now();
        nlohmann::json record = std::visit([&](const auto& e) { return apply(ctx, e); }, edits.edits[i]);
        record["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        applied.push_back(std::move(record));
        stage.update(double(i + 1) / double(edits.edits.size()));
    }
    return {{"file", edits.file}, {"applied", applied}};
}

}  // namespace jawmesh
