#include "cli/Pipeline.h"

#include "cli/EvalReport.h"
#include "fe/FeDecks.h"
#include "io/Error.h"
#include "io/GmshWriter.h"
#include "io/PolyWriter.h"
#include "io/LabelsJson.h"
#include "io/MeditWriter.h"
#include "io/ResourceUsage.h"
#include "io/AtomicFile.h"
#include "io/VtuWriter.h"
#include "levelset/LabelFieldIO.h"
#include "levelset/MeshToLevelSet.h"
#include "tet/ElementQuality.h"
#include "tet/RegionSurfaces.h"
#include "tet/ValidateTetMesh.h"

#include <embree3/rtcore.h>
#include <openvdb/openvdb.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>

namespace jawmesh {
namespace {

using Clock = std::chrono::steady_clock;

/// Times named steps into run.json's "stages" (seconds and peak memory after each step).
class StageLog {
public:
    explicit StageLog(nlohmann::json& record) : record_(record) {}
    template <typename F>
    auto run(const std::string& name, Progress& progress, F&& step) {
        ProgressStage stage(progress, name);
        const auto start = Clock::now();
        struct Finish {
            StageLog& log;
            const std::string& name;
            Clock::time_point start;
            ~Finish() {
                log.record_["stages"].push_back(
                    {{"name", name},
                     {"seconds", std::chrono::duration<double>(Clock::now() - start).count()},
                     {"peak_memory_bytes", peakResidentMemoryBytes()}});
            }
        } finish{*this, name, start};
        return step();
    }

private:
    nlohmann::json& record_;
};

std::vector<int> teethInField(const LabelField& field) {
    std::vector<int> unns;
    for (const auto& [label, grid] : field.distances)
        if (labelKind(label) == LabelKind::Tooth) unns.push_back(labelUnn(label));
    return unns;
}

template <typename T>
void readKey(const nlohmann::json& j, const char* key, T& value) {
    if (j.contains(key)) value = j.at(key).get<T>();
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
    std::ifstream in(path);
    if (!in) throw Error(path, "cannot open config file");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(path, std::string("invalid JSON: ") + e.what());
    }
    if (!j.is_object()) throw Error(path, "config must be a JSON object");
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
}

nlohmann::json runJaw(const JawCase& jawCase, const RunOptions& options, const std::string& outJawDir,
                      Progress& progress) {
    const std::string jaw = jawName(jawCase.jaw);
    nlohmann::json record = {
        {"jaw", jaw},
        {"options", runOptionsToJson(options)},
        {"versions",
         {{"jawmesh", JAWMESH_VERSION},
          {"openvdb", OPENVDB_LIBRARY_VERSION_STRING},
          {"embree", RTC_VERSION_STRING},
          {"tetgen", "1.5"}}},
        {"stages", nlohmann::json::array()},
    };
    const auto start = Clock::now();
    StageLog log(record);

    std::map<int, ToothAxes> caseAxes;  // from the case; computed from the mesh when absent
    LabelField field;
    if (!options.fromVdb.empty()) {
        field = log.run(jaw + ": read label field", progress, [&] { return readLabelField(options.fromVdb); });
    } else {
        JawSurfaces surfaces =
            log.run(jaw + ": read", progress, [&] { return loadJaw(jawCase, options.load, progress); });
        caseAxes = surfaces.axes;
        record["input"] = {{"bone_triangles", surfaces.bone.triangles.size()}, {"teeth", surfaces.teeth.size()}};
        for (const std::string& note : surfaces.notes) record["notes"].push_back(note);
        openvdb::FloatGrid::Ptr bone;
        std::map<int, openvdb::FloatGrid::ConstPtr> teeth;
        log.run(jaw + ": level sets", progress, [&] {
            bone = meshToLevelSet(surfaces.bone, options.voxelSizeMm, options.bandVoxels, progress);
            for (const auto& [unn, mesh] : surfaces.teeth)
                teeth[unn] = meshToLevelSet(mesh, options.voxelSizeMm, options.bandVoxels, progress);
        });
        CarveOptions carve = options.carve;
        if (carve.axes.empty()) carve.axes = surfaces.axes;
        CarveSummary summary;
        field = log.run(jaw + ": carve", progress,
                        [&] { return carveJaw(jawCase.jaw, *bone, teeth, carve, summary, progress); });
        for (const std::string& w : summary.warnings) record["warnings"].push_back(w);
        if (options.writeLevelSets)
            log.run(jaw + ": write level sets", progress,
                    [&] { writeLabelField(field, outJawDir + "/levelsets"); });
    }
    const std::vector<int> teeth = teethInField(field);

    ExtractStats extractStats;
    InterfaceComplex complex =
        log.run(jaw + ": interface surface", progress, [&] {
            ExtractOptions extract = options.extract;
            extract.findSeeds = false;  // simplification places them on its output
            return extractInterfaces(field, extract, progress, &extractStats);
        });
    field = LabelField{};  // the grids are no longer needed; free them before TetGen
    SimplifyStats simplifyStats;
    complex = log.run(jaw + ": simplify surface", progress,
                      [&] { return simplifyInterfaces(complex, options.simplify, progress, &simplifyStats); });
    record["surface"] = {{"vertices", complex.surface.vertices.size()}, {"triangles", complex.surface.triangles.size()},
                         {"seeds", complex.seeds.size()}, {"simplify", toJson(simplifyStats)},
                         {"enclosed_outside_pockets_filled",
                          {{"pockets", extractStats.pocketsFilled}, {"voxels", extractStats.pocketVoxelsFilled}}}};

    TetStats tetStats;
    TetMesh mesh = log.run(jaw + ": tetrahedralize", progress, [&] {
        try {
            return tetrahedralize(complex, options.tet, progress, &tetStats);
        } catch (const Error& e) {
            // The surface took most of the run to make: keep it, so the failure can be studied
            // (`tetgen -pA <file>`, a viewer) without running everything again.
            const std::string poly = outJawDir + "/failed_surface/" + jaw + ".poly";
            writeTetgenPoly(complex, poly);
            throw Error(std::string(e.what()) + " (the interface surface is in " + poly + ")");
        }
    });
    const SliverStats& sl = tetStats.slivers;
    record["tetgen"] = {{"switches", tetStats.switches},
                        {"attempts", tetStats.attempts},
                        {"seconds", tetStats.seconds},
                        {"sliver_improvement",
                         {{"below_target_before", sl.badBefore},
                          {"below_target_after", sl.badAfter},
                          {"min_dihedral_before_deg", sl.minDihedralBeforeDeg},
                          {"min_dihedral_after_deg", sl.minDihedralAfterDeg},
                          {"smoothed", sl.smoothed},
                          {"flips23", sl.flips23},
                          {"flips32", sl.flips32},
                          {"splits", sl.splits},
                          {"face_splits", sl.faceSplits},
                          {"cavity_stars", sl.cavityStars},
                          {"seconds", sl.seconds}}}};

    const ValidationReport report =
        log.run(jaw + ": validate", progress, [&] { return requireValid(mesh, teeth); });
    const QualityStats quality = measureQuality(mesh, options.tet.minDihedralDeg);
    record["validation"] = toJson(report);
    record["quality"] = {{"min_dihedral_deg", quality.minDihedralDeg},
                         {"max_dihedral_deg", quality.maxDihedralDeg},
                         {"max_radius_edge", quality.maxRadiusEdge},
                         {"tets_below_min_dihedral", quality.belowDihedralThreshold}};
    record["mesh"] = {{"nodes", mesh.nodes.size()}, {"tets", mesh.tets.size()}};

    log.run(jaw + ": write", progress, [&] {
        const std::string vol = outJawDir + "/volumetric_meshes/";
        writeGmsh(mesh, vol + jaw + ".msh");
        writeVtu(mesh, vol + jaw + ".vtu");
        writeMedit(mesh, vol + jaw + ".mesh");
        writeLabelsJson(mesh.labels, vol + "labels.json");
        writeRegionSurfaces(mesh, outJawDir + "/surface_meshes");
    });
    // The decks are a convenience on top of the validated mesh: a jaw where no tooth can be
    // loaded still gets its mesh, with the reason in run.json.
    log.run(jaw + ": fe decks", progress, [&] {
        try {
            // Relative to the jaw folder: the folder may be renamed afterwards (a batch does).
            for (const std::string& p : writeTippingDecks(mesh, caseAxes, outJawDir))
                record["fe_decks"].push_back(std::filesystem::path(p).lexically_relative(outJawDir).generic_string());
        } catch (const Error& e) {
            record["warnings"].push_back(std::string("tipping decks not written: ") + e.what());
        }
    });

    record["eval"] = log.run(jaw + ": eval", progress, [&] {
        return runReport(mesh, jawCase, options.load, options.carve.pdlThicknessMm, outJawDir, progress);
    });
    record["seconds"] = std::chrono::duration<double>(Clock::now() - start).count();
    record["peak_memory_bytes"] = peakResidentMemoryBytes();
    writeFileAtomically(outJawDir + "/run.json", [&](std::ostream& out) { out << record.dump(2) << '\n'; }, false);
    return record;
}

}  // namespace jawmesh
