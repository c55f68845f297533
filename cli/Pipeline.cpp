#include "cli/Pipeline.h"

#include "batch/MemoryEstimate.h"
#include "cli/EvalReport.h"
#include "fe/FeDecks.h"
#include "io/Error.h"
#include "io/GmshWriter.h"
#include "io/PolyWriter.h"
#include "io/LabelsJson.h"
#include "io/MeditWriter.h"
#include "io/ResourceUsage.h"
#include "io/AtomicFile.h"
#include "io/StagedFolder.h"
#include "io/VtuWriter.h"
#include "levelset/InsideOverlap.h"
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
#include <sstream>

namespace jawmesh {
namespace {

using Clock = std::chrono::steady_clock;

/// Times named steps into run.json's "stages" (wall and CPU seconds, peak memory after each step).
class StageLog {
public:
    explicit StageLog(nlohmann::json& record) : record_(record) {}
    template <typename F>
    auto run(const std::string& name, Progress& progress, F&& step) {
        returnFreedMemory();  // what the last stage freed, before this one maps its own
        ProgressStage stage(progress, name);
        const auto start = Clock::now();
        struct Finish {
            StageLog& log;
            const std::string& name;
            Clock::time_point start;
            double startCpuSeconds;
            ~Finish() {
                log.record_["stages"].push_back(
                    {{"name", name},
                     {"seconds", std::chrono::duration<double>(Clock::now() - start).count()},
                     {"cpu_seconds", processCpuSeconds() - startCpuSeconds},
                     {"peak_memory_bytes", peakResidentMemoryBytes()}});
            }
        } finish{*this, name, start, processCpuSeconds()};
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

}  // namespace

std::string toothSource(const JawCase& jawCase, int unn) {
    const auto file = jawCase.toothPaths.find(unn);
    if (file != jawCase.toothPaths.end()) return file->second;
    return jawCase.allTeethPath + " (tooth " + std::to_string(unn) + ")";
}

JawLevelSets jawLevelSets(const JawSurfaces& surfaces, const JawCase& jawCase, double voxelMm, double bandVoxels,
                          Progress& progress) {
    auto levelSet = [&](const SurfaceMesh& mesh, Label label, const std::string& source) {
        try {
            openvdb::FloatGrid::Ptr grid = meshToLevelSet(mesh, voxelMm, bandVoxels, progress);
            grid->setName(labelName(label));
            return grid;
        } catch (const Error& e) {
            throw Error(source, e.reason());
        }
    };
    JawLevelSets sets;
    sets.bone = levelSet(surfaces.bone, boneLabel(surfaces.jaw), jawCase.bonePath);
    for (const auto& [unn, mesh] : surfaces.teeth) sets.teeth[unn] = levelSet(mesh, toothLabel(unn), toothSource(jawCase, unn));
    // Teeth in contact overlap a little and the carving splits them; a large shared volume is a
    // segmentation error (one tooth exported twice, two teeth merged) that would mesh silently wrong.
    for (auto a = sets.teeth.begin(); a != sets.teeth.end(); ++a)
        for (auto b = std::next(a); b != sets.teeth.end(); ++b) {
            progress.checkCancelled();
            const double shared = insideOverlapFraction(*a->second, *b->second);
            if (shared > kHeavyToothOverlapFraction)
                throw Error(toothSource(jawCase, b->first),
                            "overlaps " + toothSource(jawCase, a->first) + " by " +
                                std::to_string(static_cast<int>(shared * 100 + 0.5)) +
                                "% of the smaller tooth's volume: the same tooth exported twice, or two teeth "
                                "segmented into each other? Fix the segmentation.");
        }
    return sets;
}

void requireBoneContact(const CarveSummary& summary, const JawCase& jawCase, const CarveOptions& options) {
    for (const ToothCarveSummary& t : summary.teeth)
        if (t.pdlVolumeMm3 <= 0) {
            std::ostringstream reason;
            reason << "tooth " << t.unn << " does not reach the bone (no root surface within the "
                   << options.gapBridgeMm << " mm gap bridge of a socket), so it gets no PDL; is the file in the "
                   << "bone's coordinate frame and of this jaw?";
            throw Error(toothSource(jawCase, t.unn), reason.str());
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
        requireMemoryFits(surfaces, options.voxelSizeMm, options.memoryLimitBytes,
                          std::filesystem::path(jawCase.bonePath).parent_path().parent_path().string());
        caseAxes = surfaces.axes;
        record["input"] = {{"bone_triangles", surfaces.bone.triangles.size()}, {"teeth", surfaces.teeth.size()}};
        for (const std::string& note : surfaces.notes) record["notes"].push_back(note);
        const JawLevelSets levelSets = log.run(jaw + ": level sets", progress, [&] {
            return jawLevelSets(surfaces, jawCase, options.voxelSizeMm, options.bandVoxels, progress);
        });
        CarveOptions carve = options.carve;
        if (carve.axes.empty()) carve.axes = surfaces.axes;
        CarveSummary summary;
        field = log.run(jaw + ": carve", progress,
                        [&] { return carveJaw(jawCase.jaw, *levelSets.bone, levelSets.teeth, carve, summary, progress); });
        for (const std::string& w : summary.warnings) record["warnings"].push_back(w);
        requireBoneContact(summary, jawCase, carve);
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
            extract.adaptive = matchedTo(options.simplify, extract.adaptive);
            return extractInterfaces(std::move(field), extract, progress, &extractStats);
        });
    field = LabelField{};  // extraction consumed the grids
    SimplifyStats simplifyStats;
    complex = log.run(jaw + ": simplify surface", progress,
                      [&] { return simplifyInterfaces(complex, options.simplify, progress, &simplifyStats); });
    record["surface"] = {{"vertices", complex.surface.vertices.size()}, {"triangles", complex.surface.triangles.size()},
                         {"seeds", complex.seeds.size()}, {"simplify", toJson(simplifyStats)},
                         {"enclosed_outside_pockets_filled",
                          {{"pockets", extractStats.pocketsFilled}, {"voxels", extractStats.pocketVoxelsFilled}}},
                         {"region_fragments_absorbed",
                          {{"fragments", extractStats.fragmentsAbsorbed}, {"voxels", extractStats.fragmentVoxelsAbsorbed}}},
                         {"adaptive", toJson(extractStats.adaptive)}};

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
    nlohmann::json holes = nlohmann::json::array();
    for (const FilledHole& h : tetStats.holeRepair.filled)
        holes.push_back({{"between", {labelName(h.pair[0]), labelName(h.pair[1])}},
                         {"boundary_edges", h.boundaryEdges},
                         {"diameter_mm", h.diameterMm},
                         {"centre_mm", {h.centre.x(), h.centre.y(), h.centre.z()}},
                         {"triangles", h.triangles},
                         {"repair", holeRepairName(h.how)}});
    record["tetgen"] = {{"hole_repair",
                         {{"holes_filled", tetStats.holeRepair.filled.size()},
                          {"triangles_added", tetStats.holeRepair.trianglesAdded()},
                          {"vertices_added", tetStats.holeRepair.verticesAdded()},
                          {"triangles_removed", tetStats.holeRepair.trianglesRemoved()},
                          {"largest_hole_mm", tetStats.holeRepair.largestHoleMm()},
                          {"holes", holes}}},
                        {"switches", tetStats.switches},
                        {"attempts", tetStats.attempts},
                        {"failed_attempts", tetStats.failedAttempts},
                        {"refine_rounds", tetStats.refineRounds},
                        {"refined_edges", tetStats.refinedEdges},
                        {"refinement_child_peak_memory_bytes", tetStats.childPeakMemoryBytes},
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
                          {"interface_insertions", sl.interfaceInsertions},
                          {"edge_removals", sl.edgeRemovals},
                          {"lookaheads", sl.lookaheads},
                          {"interface_pushes", sl.interfacePushes},
                          {"largest_push_mm", sl.largestPushMm},
                          {"passes", sl.passes},
                          {"seconds", sl.seconds}}}};

    const ValidationReport report =
        log.run(jaw + ": validate", progress, [&] { return requireValid(mesh, teeth); });
    const QualityStats quality = measureQuality(mesh, options.tet.slivers.targetMinDihedralDeg);
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

nlohmann::json runJawStaged(const JawCase& jawCase, const RunOptions& options, const std::string& outJawDir,
                            Progress& progress) {
    StagedFolder staged(outJawDir);
    nlohmann::json record;
    try {
        record = runJaw(jawCase, options, staged.path(), progress);
    } catch (const Error& e) {
        throw Error(keepFailedSurface(staged.path(), outJawDir + "/failed_surface", e.what()));
    }
    staged.commit(StagedFolder::Mode::Replace);  // a jaw folder holds one run (no stale teeth of an earlier one)
    return record;
}

std::string keepFailedSurface(const std::string& outJawDir, const std::string& keptDir, std::string message) {
    namespace fs = std::filesystem;
    const std::string from = outJawDir + "/failed_surface";
    std::error_code ec;
    if (!fs::is_directory(from, ec)) return message;
    fs::remove_all(keptDir, ec);
    fs::create_directories(fs::path(keptDir).parent_path(), ec);
    fs::rename(from, keptDir, ec);
    if (ec) return message + " (could not keep it: " + ec.message() + ")";
    for (std::size_t at = message.find(from); at != std::string::npos; at = message.find(from, at + keptDir.size()))
        message.replace(at, from.size(), keptDir);
    return message;
}

}  // namespace jawmesh
