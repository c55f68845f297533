// Implements cli/Pipeline.h; what it computes, its rules and its contract are documented there.
#include "cli/Pipeline.h"

#include "batch/MemoryEstimate.h"
#include "cli/EvalReport.h"
#include "fe/FeDecks.h"
#include "fe/ToothAxesFromShape.h"
#include "io/Error.h"
#include "io/GmshWriter.h"
#include "io/HugePageMalloc.h"
#include "io/PolyWriter.h"
#include "io/LabelsJson.h"
#include "io/MeditWriter.h"
#include "io/ResourceUsage.h"
#include "io/AtomicFile.h"
#include "io/StagedFolder.h"
#include "io/VtuWriter.h"
#include "levelset/JawEdits.h"
#include "levelset/JawInput.h"
#include "levelset/JawLevelSetsIO.h"
#include "levelset/JawLevelSets.h"
#include "levelset/LabelFieldIO.h"
#include "tet/ElementQuality.h"
#include "tet/RegionSurfaces.h"
#include "tet/ValidateTetMesh.h"

#include <embree3/rtcore.h>
#include <openvdb/openvdb.h>
#include <tbb/task_group.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
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
        if (isToothLike(labelKind(label))) unns.push_back(labelUnn(label));
    return unns;
}

/// Writes the validated mesh (its volume files, labels and region surfaces) and the tipping decks
/// into outJawDir; returns {"stages": their timings, "fe_decks": the decks' paths relative to
/// outJawDir, "warnings": ...}. The decks are a convenience on top of the mesh: a jaw where no
/// tooth can be loaded still gets its mesh, with the reason as a warning. Throws Error when a
/// mesh file cannot be written.
nlohmann::json writeOutputs(const TetMesh& mesh, const std::map<int, ToothAxes>& caseAxes, const std::string& jaw,
                            const std::string& outJawDir) {
    nlohmann::json out = {{"stages", nlohmann::json::array()}, {"fe_decks", nlohmann::json::array()},
                          {"warnings", nlohmann::json::array()}};
    StageLog log(out);
    log.run(jaw + ": write", noProgress(), [&] {
        const std::string vol = outJawDir + "/volumetric_meshes/";
        writeGmsh(mesh, vol + jaw + ".msh");
        writeVtu(mesh, vol + jaw + ".vtu");
        writeMedit(mesh, vol + jaw + ".mesh");
        writeLabelsJson(mesh.labels, vol + "labels.json");
        writeRegionSurfaces(mesh, outJawDir + "/surface_meshes");
    });
    log.run(jaw + ": fe decks", noProgress(), [&] {
        try {
            // Relative to the jaw folder: the folder may be renamed afterwards (a batch does).
            std::vector<std::string> notes;
            for (const std::string& p : writeTippingDecks(mesh, caseAxes, outJawDir, {}, &notes))
                out["fe_decks"].push_back(std::filesystem::path(p).lexically_relative(outJawDir).generic_string());
            // a load direction nobody should rely on without a look
            for (const std::string& n : notes)
                if (n.find(kUncertainAxesNote) != std::string::npos) out["warnings"].push_back(n);
        } catch (const Error& e) {
            out["warnings"].push_back(std::string("tipping decks not written: ") + e.what());
        }
    });
    return out;
}

}  // namespace

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
        // what the timings ran with (io/HugePageMalloc.h)
        {"huge_pages", {{"kernel_mode", kernelHugePageMode()}, {"malloc_advises", mallocAdvisesHugePages()}}},
        {"stages", nlohmann::json::array()},
    };
    const auto start = Clock::now();
    StageLog log(record);

    std::map<int, ToothAxes> caseAxes;  // from the case; computed from the mesh when absent
    EvalOptions evalOptions;  // what the report judges the mesh against
    evalOptions.pdlTargetMm = options.carve.pdlThicknessMm;
    LabelField field;
    std::optional<JawSurfaces> input;  // kept for the report: reading it again cost a tenth of a small run
    if (!options.fromVdb.empty() && !options.edits.edits.empty())
        throw Error(options.edits.file, "edits apply to a case's level sets before carving, not to a carved folder "
                                        "(--from-vdb); use `jawmesh edit` on a folder written by --write-levelsets");
    if (!options.fromVdb.empty()) {
        field = log.run(jaw + ": read label field", progress, [&] { return readLabelField(options.fromVdb); });
        if (const auto history = readEditHistory(options.fromVdb); !history.empty()) record["edits"] = history;
    } else {
        input = log.run(jaw + ": read", progress, [&] { return loadJawInput(jawCase, options.load, progress); });
        const JawSurfaces& surfaces = *input;
        requireMemoryFits(surfaces, options.voxelSizeMm, options.memoryLimitBytes,
                          jawCase.folder);
        caseAxes = surfaces.axes;
        std::vector<int> inputTeeth;
        for (const auto& [unn, tooth] : surfaces.teeth) inputTeeth.push_back(unn);
        requireEditsFit(options.edits, inputTeeth);  // before the long stages
        record["input"] = {{"bone_triangles", surfaces.bone.triangles.size()}, {"teeth", surfaces.teeth.size()}};
        for (const std::string& note : surfaces.notes) record["notes"].push_back(note);
        CarveOptions carve = carveOptionsFor(surfaces, options.carve, options.voxelSizeMm);
        JawLevelSets levelSets = log.run(jaw + ": level sets", progress, [&] {
            return jawLevelSets(surfaces, jawCase, options.voxelSizeMm, options.bandVoxels, options.boneFarBandVoxels,
                                toothBandVoxels(carve, options.voxelSizeMm), progress);
        });
        if (surfaces.pdlKept) evalOptions.pdlTargetMm = 0.0;  // a kept PDL is measured, not judged
        if (!options.edits.edits.empty())
            record["edits"].push_back(
                log.run(jaw + ": edits", progress, [&] { return applyEdits(options.edits, levelSets, carve, progress); }));
        CarveSummary summary;
        field = log.run(jaw + ": carve", progress,
                        [&] { return carveJaw(jawCase.jaw, *levelSets.bone, levelSets.teeth, carve, summary, progress); });
        for (const std::string& w : summary.warnings) record["warnings"].push_back(w);
        record["carve"] = {{"options", toJson(carve)}, {"summary", toJson(summary)}};
        requireBoneContact(summary, jawCase, carve);
        if (options.writeLevelSets)
            log.run(jaw + ": write level sets", progress, [&] {
                writeEditableFolder(field, levelSets, jawCase.jaw, carve, record.value("edits", nlohmann::json::array()),
                                    outJawDir + "/levelsets");
            });
    }
    const std::vector<int> teeth = teethInField(field);
    std::vector<int> removedTeeth;
    if (record.contains("edits")) judgeAgainstEdits(record["edits"], evalOptions, removedTeeth);

    // The input's resolution caps the bone's bounds (a label map); a carved folder keeps the options'.
    const SimplifyOptions simplify = simplifyOptionsFor(options.simplify, input ? input->labelVoxelMm : 0.0);
    ExtractStats extractStats;
    InterfaceComplex complex =
        log.run(jaw + ": interface surface", progress, [&] {
            ExtractOptions extract = options.extract;
            extract.findSeeds = false;  // simplification places them on its output
            extract.adaptive = matchedTo(simplify, extract.adaptive);
            return extractInterfaces(std::move(field), extract, progress, &extractStats);
        });
    field = LabelField{};  // extraction consumed the grids
    SimplifyStats simplifyStats;
    complex = log.run(jaw + ": simplify surface", progress,
                      [&] { return simplifyInterfaces(complex, simplify, progress, &simplifyStats); });
    record["surface"] = {{"vertices", complex.surface.vertices.size()}, {"triangles", complex.surface.triangles.size()},
                         {"seeds", complex.seeds.size()}, {"simplify", toJson(simplifyStats)}};
    record["surface"].update(toJson(extractStats));
    record["surface"]["bone_bounds_mm"] = {{"near_teeth", simplify.boneErrorMm}, {"far", simplify.boneFarErrorMm}};

    TetStats tetStats;
    TetMesh mesh = log.run(jaw + ": tetrahedralize", progress, [&] {
        try {
            TetOptions tet = options.tet;
            tet.checkIntersections = false;  // simplifyInterfaces has checked its output exactly
            return tetrahedralize(complex, tet, progress, &tetStats);
        } catch (const Error& e) {
            // The surface took most of the run to make: keep it, so the failure can be studied
            // (`tetgen -pA <file>`, a viewer) without running everything again.
            const std::string poly = outJawDir + "/failed_surface/" + jaw + ".poly";
            writeTetgenPoly(complex, poly);
            throw Error(std::string(e.what()) + " (the interface surface is in " + poly + ")");
        }
    });
    record["tetgen"] = toJson(tetStats);

    const ValidationReport report =
        log.run(jaw + ": validate", progress, [&] { return requireValid(mesh, teeth); });
    const QualityStats quality = measureQuality(mesh, options.tet.slivers.targetMinDihedralDeg);
    record["validation"] = toJson(report);
    record["quality"] = toJson(quality);
    record["mesh"] = {{"nodes", mesh.nodes.size()}, {"tets", mesh.tets.size()}};

    // The files and decks are written while the report measures the mesh (both only read it): the
    // writers are mostly serial (2.2 s on the shared mandible) and the report leaves a core idle
    // at times. Each stage is timed on its own (their CPU seconds overlap).
    nlohmann::json outputs;  // the writers' stages and notes, merged when both are done
    tbb::task_group writers;
    writers.run([&] { outputs = writeOutputs(mesh, caseAxes, jaw, outJawDir); });
    nlohmann::json eval;
    try {
        eval = log.run(jaw + ": eval", progress, [&] {
            return runReport(mesh, jawCase, options.load, input ? &*input : nullptr, evalOptions, removedTeeth, outJawDir, progress);
        });
    } catch (...) {
        writers.wait();  // never leave the writers running on a mesh about to be freed
        throw;
    }
    writers.wait();
    auto& stages = record["stages"];  // the writers' before the eval's, as when they ran first
    stages.insert(stages.end() - 1, outputs["stages"].begin(), outputs["stages"].end());
    for (const auto& p : outputs["fe_decks"]) record["fe_decks"].push_back(p);
    for (const auto& w : outputs["warnings"]) record["warnings"].push_back(w);
    record["eval"] = eval;
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
