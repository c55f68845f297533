// Implements cli/RunOptions.h; what it computes, its rules and its contract are documented there.
#include "cli/RunOptions.h"

#include "io/Error.h"

#include <cmath>
#include <limits>
#include <fstream>
#include <sstream>

namespace jawmesh {
namespace {

template <typename T>
void readKey(const nlohmann::json& j, const char* key, T& value) {
    if (j.contains(key)) value = j.at(key).get<T>();
}

/// A number read from the config must lie in [lo, hi] (open at lo when loOpen): a voxel of 0 mm or
/// a negative thickness would otherwise fail deep inside a stage with a message about grids.
void requireRange(const std::string& name, const char* key, double value, double lo, double hi, bool loOpen = false) {
    const bool ok = std::isfinite(value) && (loOpen ? value > lo : value >= lo) && value <= hi;
    if (ok) return;
    std::ostringstream msg;
    msg << "'" << key << "' is " << value << "; it must be " << (loOpen ? "> " : ">= ") << lo << " and <= " << hi;
    throw Error(name, msg.str());
}

/// Every numeric option: its config / run.json key, where it lives, and its valid range.
struct NumberKey {
    const char* key;
    double& (*ref)(RunOptions&);
    double lo, hi;
    bool loOpen = false;
};

constexpr double kAny = std::numeric_limits<double>::infinity();

// tet_radius_edge is checked where TetGen gets it (tet/Tetrahedralize.h): its Error there keeps the
// interface surface made so far, like any other TetGen failure.
const NumberKey kNumberKeys[] = {
    {"voxel_mm", [](RunOptions& o) -> double& { return o.voxelSizeMm; }, 0, 10, true},
    {"band_voxels", [](RunOptions& o) -> double& { return o.bandVoxels; }, 1, 1000},
    {"bone_far_band_voxels", [](RunOptions& o) -> double& { return o.boneFarBandVoxels; }, 1, 1000},
    {"scale", [](RunOptions& o) -> double& { return o.load.scale; }, 0, 1e6},
    {"pdl_thickness_mm", [](RunOptions& o) -> double& { return o.carve.pdlThicknessMm; }, 0, 10, true},
    {"pdl_ratio", [](RunOptions& o) -> double& { return o.carve.pdlRatio; }, 0, 1},
    {"clearance_voxels", [](RunOptions& o) -> double& { return o.carve.clearanceVoxels; }, 0, 100},
    {"gap_bridge_mm", [](RunOptions& o) -> double& { return o.carve.gapBridgeMm; }, 0, 10},
    {"bone_shift_max_mm", [](RunOptions& o) -> double& { return o.carve.boneShiftMaxMm; }, 0, 10},
    {"apex_taper_mm", [](RunOptions& o) -> double& { return o.carve.apexTaperMm; }, 0, 100},
    {"surface_tooth_error_mm", [](RunOptions& o) -> double& { return o.simplify.toothErrorMm; }, 0, 10},
    {"surface_pdl_error_mm", [](RunOptions& o) -> double& { return o.simplify.pdlErrorMm; }, 0, 10},
    {"surface_bone_error_mm", [](RunOptions& o) -> double& { return o.simplify.boneErrorMm; }, 0, 10},
    {"surface_bone_far_error_mm", [](RunOptions& o) -> double& { return o.simplify.boneFarErrorMm; }, 0, 10},
    {"surface_bone_near_teeth_mm", [](RunOptions& o) -> double& { return o.simplify.boneNearTeethMm; }, 0, 1000},
    {"surface_pdl_max_edge_mm", [](RunOptions& o) -> double& { return o.simplify.pdlMaxEdgeMm; }, 0, 100, true},
    {"surface_cap_max_edge_mm", [](RunOptions& o) -> double& { return o.simplify.capMaxEdgeMm; }, 0, 100, true},
    {"surface_tooth_max_edge_mm", [](RunOptions& o) -> double& { return o.simplify.toothMaxEdgeMm; }, 0, 100, true},
    {"surface_bone_max_edge_mm", [](RunOptions& o) -> double& { return o.simplify.boneMaxEdgeMm; }, 0, 100, true},
    {"surface_min_angle_deg", [](RunOptions& o) -> double& { return o.simplify.minAngleDeg; }, 0, 59},
    {"surface_min_wedge_deg", [](RunOptions& o) -> double& { return o.simplify.minWedgeDeg; }, 0, 89},
    {"surface_plate_max_mm", [](RunOptions& o) -> double& { return o.simplify.plateMaxMm; }, 0, 10},
    {"surface_plate_error_fraction", [](RunOptions& o) -> double& { return o.simplify.plateErrorFraction; }, 0, 1},
    {"surface_plate_edge_factor", [](RunOptions& o) -> double& { return o.simplify.plateEdgeFactor; }, 0, 1000},
    {"tet_radius_edge", [](RunOptions& o) -> double& { return o.tet.radiusEdgeRatio; }, -kAny, kAny},
    {"tet_min_dihedral_deg", [](RunOptions& o) -> double& { return o.tet.slivers.targetMinDihedralDeg; }, 0, 60},
    {"tet_tetgen_min_dihedral_deg", [](RunOptions& o) -> double& { return o.tet.tetgenMinDihedralDeg; }, -1, 60},
    {"tet_pdl_edge_mm", [](RunOptions& o) -> double& { return o.tet.pdlEdgeMm; }, 0, 1000},
    {"tet_tooth_edge_mm", [](RunOptions& o) -> double& { return o.tet.toothEdgeMm; }, 0, 1000},
    {"tet_bone_edge_mm", [](RunOptions& o) -> double& { return o.tet.boneEdgeMm; }, 0, 1000},
    {"tet_interface_push_mm", [](RunOptions& o) -> double& { return o.tet.slivers.interfacePushMm; }, 0, 0.05},
    {"tet_outer_push_mm", [](RunOptions& o) -> double& { return o.tet.slivers.outerPushMm; }, 0, 0.05},
    {"tet_final_push_mm", [](RunOptions& o) -> double& { return o.tet.finalInterfacePushMm; }, 0, 0.05},
};

/// A whole-number key from lo to hi, when present: 2.5 levels is a mistake, not 2.
void readWholeKey(const nlohmann::json& j, const std::string& path, const char* key, int lo, int hi, int& out) {
    if (!j.contains(key)) return;
    const double value = j.at(key).get<double>();
    if (value != std::floor(value) || !(value >= lo && value <= hi))
        throw Error(path, "'" + std::string(key) + "' must be a whole number from " + std::to_string(lo) + " to " +
                              std::to_string(hi));
    out = int(value);
}

void checkRanges(const std::string& name, RunOptions& o) {
    for (const auto& k : kNumberKeys) requireRange(name, k.key, k.ref(o), k.lo, k.hi, k.loOpen);
    const int levels = o.extract.adaptive.maxLevel;
    requireRange(name, "surface_adaptive_levels", levels, 0, 5);
    const int gap = o.extract.adaptive.layerGapVoxels;
    requireRange(name, "surface_layer_gap_voxels", gap, 0, 8);
    requireRange(name, "tet_refine_rounds", o.tet.refineRounds, 0, 5);
    if (o.carve.profile) {
        requireRange(name, "pdl_profile_mm", o.carve.profile->cervical, 0, 10, true);
        requireRange(name, "pdl_profile_mm", o.carve.profile->midRoot, 0, 10, true);
        requireRange(name, "pdl_profile_mm", o.carve.profile->apical, 0, 10, true);
    }
}

}  // namespace

SimplifyOptions simplifyOptionsFor(SimplifyOptions options, double labelVoxelMm) {
    if (labelVoxelMm > 0) {
        const double bound = kLabelVoxelBoundShare * labelVoxelMm;
        options.boneErrorMm = std::min(options.boneErrorMm, bound);
        options.boneFarErrorMm = std::min(options.boneFarErrorMm, bound);
    }
    return options;
}

RunOptions defaultRunOptions() {
    RunOptions o;
    // Measured on the shared mandible (docs/BENCHMARKS.md, sessions 6 and 7): PDL interfaces with
    // edges up to 0.8 mm halve their triangles (213 k -> 107 k, the surface 399 k -> 294 k). On that
    // surface TetGen's radius-edge bound sets the count: 1.30 M tets at 1.5/10 with sizes
    // 2 / 1 / 0.3 mm, 0.99 M at 2/0, 0.75 M at 3/0 with sizes 4 / 2 / 0.6 mm (#5 allows 0.8 M); the
    // tets left under 10 deg after tet/ImproveSlivers (100-260) do not follow the bound.
    o.simplify.pdlMaxEdgeMm = 0.8;
    o.tet.boneEdgeMm = 4.0;
    o.tet.toothEdgeMm = 2.0;
    o.tet.pdlEdgeMm = 0.6;
    o.tet.radiusEdgeRatio = 3.0;
    o.tet.tetgenMinDihedralDeg = 0.0;
    // Rounds of local refinement only where the ladder's best run still leaves tets under the
    // target (the shared mandible needs none; the shared maxilla, left with 9 tets under 10 deg
    // by the ladder, met it after 2 rounds and 7 split edges, +23 s): the surface does not move
    // (docs/DESIGN.md, "Refinement rounds").
    o.tet.refineRounds = 3;
    return o;
}

nlohmann::json runOptionsToJson(const RunOptions& options) {
    RunOptions o = options;  // the key table hands out references
    nlohmann::json j = nlohmann::json::object();
    for (const auto& k : kNumberKeys) j[k.key] = k.ref(o);
    j["surface_adaptive_levels"] = o.extract.adaptive.maxLevel;
    j["surface_layer_gap_voxels"] = o.extract.adaptive.layerGapVoxels;
    j["tet_refine_rounds"] = o.tet.refineRounds;
    j["tet_lookahead_trials"] = o.tet.slivers.lookaheadTrials;
    j["write_levelsets"] = o.writeLevelSets;
    j["from_vdb"] = o.fromVdb;
    if (o.carve.profile)
        j["pdl_profile_mm"] = {o.carve.profile->cervical, o.carve.profile->midRoot, o.carve.profile->apical};
    if (!o.edits.edits.empty()) j["edits"] = toJson(o.edits).at("edits");
    return j;
}

void applyRunConfig(const std::string& path, RunOptions& o) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "cannot open config file");
    std::ostringstream text;
    text << in.rdbuf();
    applyRunConfigText(text.str(), path, o);
}

void applyRunConfigText(const std::string& text, const std::string& path, RunOptions& options) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, std::string("invalid JSON: ") + e.what());
    }
    if (!j.is_object()) throw Error(path, "config must be a JSON object");
    RunOptions o = options;  // options change only when the whole file is good
    const nlohmann::json known = runOptionsToJson(o);
    for (const auto& [key, value] : j.items())
        if (!known.contains(key) && key != "pdl_profile_mm" && key != "edits") throw Error(path, "unknown config key '" + key + "'");
    try {
        for (const auto& k : kNumberKeys) readKey(j, k.key, k.ref(o));
        readWholeKey(j, path, "surface_adaptive_levels", 0, 5, o.extract.adaptive.maxLevel);
        readWholeKey(j, path, "surface_layer_gap_voxels", 0, 8, o.extract.adaptive.layerGapVoxels);
        readWholeKey(j, path, "tet_refine_rounds", 0, 5, o.tet.refineRounds);
        int trials = int(o.tet.slivers.lookaheadTrials);
        readWholeKey(j, path, "tet_lookahead_trials", 0, 100000000, trials);
        o.tet.slivers.lookaheadTrials = std::size_t(trials);
        readKey(j, "write_levelsets", o.writeLevelSets);
        readKey(j, "from_vdb", o.fromVdb);
        if (j.contains("pdl_profile_mm")) {
            const auto p = j.at("pdl_profile_mm").get<std::vector<double>>();
            if (p.size() != 3) throw Error(path, "pdl_profile_mm needs 3 values (cervical, mid-root, apical)");
            o.carve.profile = PdlProfile{p[0], p[1], p[2]};
        }
        if (j.contains("edits")) o.edits = parseEdits({{"edits", j.at("edits")}}, path);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, std::string("wrong value type: ") + e.what());
    }
    checkRanges(path, o);
    options = o;
}

}  // namespace jawmesh
