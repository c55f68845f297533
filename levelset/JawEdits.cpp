// Implements levelset/JawEdits.h; what it computes, its rules and its contract are documented there.
#include "levelset/JawEdits.h"

#include "levelset/HealSocket.h"
#include "levelset/LowerCrest.h"

#include <chrono>
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
