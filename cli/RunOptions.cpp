#include "cli/RunOptions.h"

#include "io/Error.h"

#include <cmath>
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

void checkRanges(const std::string& name, const RunOptions& o) {
    requireRange(name, "voxel_mm", o.voxelSizeMm, 0, 10, true);
    requireRange(name, "band_voxels", o.bandVoxels, 1, 1000);
    requireRange(name, "scale", o.load.scale, 0, 1e6);
    requireRange(name, "pdl_thickness_mm", o.carve.pdlThicknessMm, 0, 10, true);
    requireRange(name, "pdl_ratio", o.carve.pdlRatio, 0, 1);
    requireRange(name, "clearance_voxels", o.carve.clearanceVoxels, 0, 100);
    requireRange(name, "gap_bridge_mm", o.carve.gapBridgeMm, 0, 10);
    requireRange(name, "surface_tooth_error_mm", o.simplify.toothErrorMm, 0, 10);
    requireRange(name, "surface_bone_error_mm", o.simplify.boneErrorMm, 0, 10);
    requireRange(name, "surface_bone_far_error_mm", o.simplify.boneFarErrorMm, 0, 10);
    requireRange(name, "surface_bone_near_teeth_mm", o.simplify.boneNearTeethMm, 0, 1000);
    requireRange(name, "surface_min_angle_deg", o.simplify.minAngleDeg, 0, 59);
    requireRange(name, "surface_min_wedge_deg", o.simplify.minWedgeDeg, 0, 89);
    // tet_radius_edge is checked where TetGen gets it (tet/Tetrahedralize.h): its Error there
    // keeps the interface surface made so far, like any other TetGen failure.
    requireRange(name, "tet_min_dihedral_deg", o.tet.minDihedralDeg, 0, 60);
    requireRange(name, "tet_pdl_edge_mm", o.tet.pdlEdgeMm, 0, 1000);
    requireRange(name, "tet_tooth_edge_mm", o.tet.toothEdgeMm, 0, 1000);
    requireRange(name, "tet_bone_edge_mm", o.tet.boneEdgeMm, 0, 1000);
    if (o.carve.profile) {
        requireRange(name, "pdl_profile_mm", o.carve.profile->cervical, 0, 10, true);
        requireRange(name, "pdl_profile_mm", o.carve.profile->midRoot, 0, 10, true);
        requireRange(name, "pdl_profile_mm", o.carve.profile->apical, 0, 10, true);
    }
}

}  // namespace

RunOptions defaultRunOptions() {
    RunOptions o;
    o.tet.pdlEdgeMm = 0.3;
    o.tet.toothEdgeMm = 1.0;
    o.tet.boneEdgeMm = 2.0;
    return o;
}

nlohmann::json runOptionsToJson(const RunOptions& o) {
    nlohmann::json j = {
        {"voxel_mm", o.voxelSizeMm},
        {"band_voxels", o.bandVoxels},
        {"scale", o.load.scale},
        {"pdl_thickness_mm", o.carve.pdlThicknessMm},
        {"pdl_ratio", o.carve.pdlRatio},
        {"clearance_voxels", o.carve.clearanceVoxels},
        {"gap_bridge_mm", o.carve.gapBridgeMm},
        {"surface_tooth_error_mm", o.simplify.toothErrorMm},
        {"surface_bone_error_mm", o.simplify.boneErrorMm},
        {"surface_bone_far_error_mm", o.simplify.boneFarErrorMm},
        {"surface_bone_near_teeth_mm", o.simplify.boneNearTeethMm},
        {"surface_min_angle_deg", o.simplify.minAngleDeg},
        {"surface_min_wedge_deg", o.simplify.minWedgeDeg},
        {"tet_radius_edge", o.tet.radiusEdgeRatio},
        {"tet_min_dihedral_deg", o.tet.minDihedralDeg},
        {"tet_pdl_edge_mm", o.tet.pdlEdgeMm},
        {"tet_tooth_edge_mm", o.tet.toothEdgeMm},
        {"tet_bone_edge_mm", o.tet.boneEdgeMm},
        {"write_levelsets", o.writeLevelSets},
        {"from_vdb", o.fromVdb},
    };
    if (o.carve.profile)
        j["pdl_profile_mm"] = {o.carve.profile->cervical, o.carve.profile->midRoot, o.carve.profile->apical};
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
        if (!known.contains(key) && key != "pdl_profile_mm") throw Error(path, "unknown config key '" + key + "'");
    try {
        readKey(j, "voxel_mm", o.voxelSizeMm);
        readKey(j, "band_voxels", o.bandVoxels);
        readKey(j, "scale", o.load.scale);
        readKey(j, "pdl_thickness_mm", o.carve.pdlThicknessMm);
        readKey(j, "pdl_ratio", o.carve.pdlRatio);
        readKey(j, "clearance_voxels", o.carve.clearanceVoxels);
        readKey(j, "gap_bridge_mm", o.carve.gapBridgeMm);
        readKey(j, "surface_tooth_error_mm", o.simplify.toothErrorMm);
        readKey(j, "surface_bone_error_mm", o.simplify.boneErrorMm);
        readKey(j, "surface_bone_far_error_mm", o.simplify.boneFarErrorMm);
        readKey(j, "surface_bone_near_teeth_mm", o.simplify.boneNearTeethMm);
        readKey(j, "surface_min_angle_deg", o.simplify.minAngleDeg);
        readKey(j, "surface_min_wedge_deg", o.simplify.minWedgeDeg);
        readKey(j, "tet_radius_edge", o.tet.radiusEdgeRatio);
        readKey(j, "tet_min_dihedral_deg", o.tet.minDihedralDeg);
        readKey(j, "tet_pdl_edge_mm", o.tet.pdlEdgeMm);
        readKey(j, "tet_tooth_edge_mm", o.tet.toothEdgeMm);
        readKey(j, "tet_bone_edge_mm", o.tet.boneEdgeMm);
        readKey(j, "write_levelsets", o.writeLevelSets);
        readKey(j, "from_vdb", o.fromVdb);
        if (j.contains("pdl_profile_mm")) {
            const auto p = j.at("pdl_profile_mm").get<std::vector<double>>();
            if (p.size() != 3) throw Error(path, "pdl_profile_mm needs 3 values (cervical, mid-root, apical)");
            o.carve.profile = PdlProfile{p[0], p[1], p[2]};
        }
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, std::string("wrong value type: ") + e.what());
    }
    checkRanges(path, o);
    options = o;
}

}  // namespace jawmesh
