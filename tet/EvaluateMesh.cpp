// Implements tet/EvaluateMesh.h; what it computes, its rules and its contract are documented there.
#include "tet/EvaluateMesh.h"

#include "filters/PdlThickness.h"
#include "filters/SurfaceDistance.h"
#include "filters/WeightedDistribution.h"
#include "io/Angles.h"
#include "io/Error.h"
#include "io/ParallelInOrder.h"
#include "io/ResourceUsage.h"
#include "tet/ElementQuality.h"
#include "tet/RegionSurfaces.h"
#include "tet/ValidateTetMesh.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <tuple>
#include <utility>

namespace jawmesh {
namespace {

using Json = nlohmann::json;

/// JSON has no infinity: a flat tet's radius-edge ratio is written as null.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json toJson(const Distribution& d) {
    return {{"count", d.count}, {"weight", d.totalWeight}, {"min", number(d.min)},   {"p05", number(d.p05)},
            {"median", number(d.median)}, {"p95", number(d.p95)}, {"mean", number(d.mean)}, {"max", number(d.max)}};
}

Json toJson(const DistanceSummary& s) {
    Json j = toJson(s.distance);
    j["area_mm2"] = s.areaMm2;
    j["max_at"] = {s.maxAt.x(), s.maxAt.y(), s.maxAt.z()};
    return j;
}

std::string kindName(LabelKind k) {
    switch (k) {
    case LabelKind::Bone: return "bone";
    case LabelKind::Tooth: return "tooth";
    case LabelKind::Pdl: return "pdl";
    case LabelKind::Implant: return "implant";
    default: return "outside";
    }
}

/// The triangles of s with keep[t] (vertices kept as they are: unused ones are never sampled).
SurfaceMesh selectTriangles(const SurfaceMesh& s, const std::function<bool(std::size_t)>& keep) {
    SurfaceMesh out;
    out.vertices = s.vertices;
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
        if (keep(t)) out.triangles.push_back(s.triangles[t]);
    return out;
}

std::size_t usedVertexCount(const SurfaceMesh& s) {
    std::vector<char> used(s.vertices.size(), 0);
    for (const Tri& t : s.triangles)
        for (std::int32_t v : t) used[static_cast<std::size_t>(v)] = 1;
    return static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
}

// ---- element quality ---------------------------------------------------------------------------

struct Measure {
    const char* name;
    double (*value)(const TetShape&);
    double histLo, histHi;  // histogram range; values outside land in the end bins
};

const Measure kMeasures[] = {
    {"radius_ratio", [](const TetShape& s) { return s.radiusRatio; }, 0.0, 1.0},
    {"volume_edge_ratio", [](const TetShape& s) { return s.volumeEdgeRatio; }, 0.0, 1.0},
    {"radius_edge_ratio", [](const TetShape& s) { return s.radiusEdgeRatio; }, 0.6, 3.0},
    {"min_dihedral_deg", [](const TetShape& s) { return s.minDihedralDeg; }, 0.0, 90.0},
    {"max_dihedral_deg", [](const TetShape& s) { return s.maxDihedralDeg; }, 60.0, 180.0},
};

Json qualityJson(const TetMesh& mesh, const std::vector<TetShape>& shapes, const EvalOptions& o, Json& regions) {
    Json quality;
    quality["regular_tet"] = {{"radius_ratio", 1.0},
                              {"volume_edge_ratio", 1.0},
                              {"radius_edge_ratio", kRegularRadiusEdgeRatio},
                              {"min_dihedral_deg", degrees(std::acos(1.0 / 3.0))},
                              {"max_dihedral_deg", degrees(std::acos(1.0 / 3.0))}};
    std::map<Label, std::vector<std::size_t>> tetsOf;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) tetsOf[mesh.labels[t]].push_back(t);
    for (const Measure& m : kMeasures) {
        std::vector<double> all(shapes.size());
        for (std::size_t t = 0; t < shapes.size(); ++t) all[t] = m.value(shapes[t]);
        quality["overall"][m.name] = toJson(summarizeUnweighted(all));
        Json hist = {{"lo", m.histLo}, {"hi", m.histHi}, {"bins", o.histogramBins}, {"counts", Json::object()}};
        std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> byKind;
        for (auto& region : regions) {
            const Label label = region["label"].get<Label>();
            const auto& tets = tetsOf[label];
            std::vector<double> v(tets.size());
            double lo = INFINITY, hi = -INFINITY, sum = 0;
            for (std::size_t i = 0; i < tets.size(); ++i) {
                v[i] = all[tets[i]];
                lo = std::min(lo, v[i]);
                hi = std::max(hi, v[i]);
                sum += v[i];
            }
            region["quality"][m.name] = {{"min", number(lo)}, {"mean", number(sum / static_cast<double>(v.size()))}, {"max", number(hi)}};
            auto& kind = byKind[region["kind"].get<std::string>()];
            kind.first.insert(kind.first.end(), v.begin(), v.end());
        }
        for (auto& [kind, values] : byKind)
            hist["counts"][kind] =
                weightedHistogram(values.first, std::vector<double>(values.first.size(), 1.0), m.histLo, m.histHi, o.histogramBins);
        quality["histograms"][m.name] = hist;
    }
    std::size_t below = 0;
    for (const TetShape& s : shapes) below += s.minDihedralDeg < o.minDihedralDeg;
    quality["tets_below_min_dihedral"] = below;
    quality["min_dihedral_threshold_deg"] = o.minDihedralDeg;
    return quality;
}

// ---- distances to the input --------------------------------------------------------------------

/// Two-sided distances between an output surface split into parts (outputPart[t] indexes `names`)
/// and its input surface; the input's triangles take the part of their nearest output face.
Json twoSidedDistances(const SurfaceMesh& output, const std::vector<int>& outputPart, const SurfaceMesh& input,
                       const std::vector<const char*>& names, const EvalOptions& o, Progress& progress) {
    const int parts = static_cast<int>(names.size());
    const TriangleBvh outBvh = buildTriangleBvh(output), inBvh = buildTriangleBvh(input);
    const DistanceSamples outSamples = sampleDistances(output, inBvh, o.sampleSpacingMm, progress);
    const auto outSummary = summarizeDistances(output, outSamples, outputPart, parts, inBvh, o.hausdorffToleranceMm, progress);
    const DistanceSamples inSamples = sampleDistances(input, outBvh, o.sampleSpacingMm, progress);
    std::vector<int> inputPart(input.triangles.size());
    for (std::size_t t = 0; t < inputPart.size(); ++t)
        inputPart[t] = outputPart[static_cast<std::size_t>(inSamples.closestTriangle[static_cast<std::size_t>(inSamples.firstOfTriangle[t])])];
    const auto inSummary = summarizeDistances(input, inSamples, inputPart, parts, outBvh, o.hausdorffToleranceMm, progress);

    Json j;
    double wholeMax = 0, wholeMeanArea = 0, wholeArea = 0;
    for (std::size_t g = 0; g < names.size(); ++g) {
        const DistanceSummary& a = outSummary[g];
        const DistanceSummary& b = inSummary[g];
        Json p;
        p["output_to_input"] = toJson(a);
        p["input_to_output"] = toJson(b);
        const double area = a.areaMm2 + b.areaMm2;
        const double hausdorff = std::max(a.distance.max, b.distance.max);
        p["hausdorff_mm"] = hausdorff;
        p["mean_mm"] = area > 0 ? (a.distance.mean * a.areaMm2 + b.distance.mean * b.areaMm2) / area : 0.0;
        p["present"] = a.distance.count > 0 || b.distance.count > 0;
        j[names[g]] = p;
        wholeMax = std::max(wholeMax, hausdorff);
        wholeMeanArea += p["mean_mm"].get<double>() * area;
        wholeArea += area;
    }
    j["whole"] = {{"hausdorff_mm", wholeMax}, {"mean_mm", wholeArea > 0 ? wholeMeanArea / wholeArea : 0.0}};
    return j;
}

/// Jaw-level row over several domains' parts: max of the maxima, area-weighted mean.
Json aggregateParts(const Json& domains, const std::string& kind, const std::string& part) {
    double maxMm = 0, meanArea = 0, area = 0;
    int count = 0;
    for (const Json& d : domains) {
        if (d["kind"] != kind || !d["parts"][part]["present"].get<bool>()) continue;
        const Json& p = d["parts"][part];
        const double a = p["output_to_input"]["area_mm2"].get<double>() + p["input_to_output"]["area_mm2"].get<double>();
        maxMm = std::max(maxMm, p["hausdorff_mm"].get<double>());
        meanArea += p["mean_mm"].get<double>() * a;
        area += a;
        ++count;
    }
    return {{"domains", count}, {"hausdorff_mm", maxMm}, {"mean_mm", area > 0 ? meanArea / area : 0.0}};
}

bool againstPdlOrBone(Label other) {
    return other != kOutsideLabel && (labelKind(other) == LabelKind::Pdl || labelKind(other) == LabelKind::Bone);
}

/// Part of each face of a tooth's boundary: 1 root (against its PDL or the bone), 2 the cervical
/// band (any corner within bandMm of a root face), 0 the rest of the crown.
std::vector<int> toothParts(const RegionBoundary& b, double bandMm) {
    std::vector<int> part(b.otherSide.size());
    for (std::size_t t = 0; t < part.size(); ++t) part[t] = againstPdlOrBone(b.otherSide[t]) ? 1 : 0;
    const SurfaceMesh root = selectTriangles(b.surface, [&](std::size_t t) { return part[t] == 1; });
    if (root.triangles.empty() || bandMm <= 0) return part;
    const TriangleBvh rootBvh = buildTriangleBvh(root);
    const double band2 = bandMm * bandMm;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, part.size(), 4096), [&](const auto& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            if (part[t] != 0) continue;
            for (std::int32_t v : b.surface.triangles[t])
                if (closestTriangle(rootBvh, b.surface.vertices[static_cast<std::size_t>(v)]).squaredDistanceMm2 <= band2) {
                    part[t] = 2;
                    break;
                }
        }
    });
    return part;
}

/// A wrong --input (another patient, another jaw, metres) would make every nearest-triangle query
/// crawl through the whole tree and report nonsense: refuse it when the boxes barely overlap.
void requireInputOverlapsMesh(const TetMesh& mesh, const JawSurfaces& input) {
    BBox meshBox, inputBox = boundingBox(input.bone);
    for (const Vec3& p : mesh.nodes) meshBox.extend(p);
    for (const auto& [unn, s] : input.teeth) inputBox.extend(boundingBox(s));
    if (inputBox.empty()) return;
    BBox common;
    common.min = meshBox.min.cwiseMax(inputBox.min);
    common.max = meshBox.max.cwiseMin(inputBox.max);
    const auto volume = [](const BBox& b) { return b.empty() ? 0.0 : b.size().prod(); };
    if (volume(common) < 0.5 * std::min(volume(meshBox), volume(inputBox))) {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "the input surfaces do not match the mesh (mesh box (%.1f %.1f %.1f)-(%.1f %.1f %.1f) mm, input box "
                      "(%.1f %.1f %.1f)-(%.1f %.1f %.1f) mm overlap by less than half): wrong input folder?",
                      meshBox.min.x(), meshBox.min.y(), meshBox.min.z(), meshBox.max.x(), meshBox.max.y(), meshBox.max.z(),
                      inputBox.min.x(), inputBox.min.y(), inputBox.min.z(), inputBox.max.x(), inputBox.max.y(), inputBox.max.z());
        throw Error(buf);
    }
}

// ---- verdict -----------------------------------------------------------------------------------

Json verdict(const Json& report, const EvalOptions& o) {
    Json checks = Json::array();
    const auto add = [&](const std::string& name, const std::string& status, const std::string& detail) {
        checks.push_back({{"name", name}, {"status", status}, {"detail", detail}});
    };
    char buf[256];
    const Json& v = report["validation"];
    if (v["valid"].get<bool>()) {
        add("conformity", "pass", "conformal, manifold, every tooth with its PDL, no shared nodes between teeth");
    } else {
        std::snprintf(buf, sizeof buf, "%zu structural violation(s)", v["violation_count"].get<std::size_t>());
        add("conformity", "fail", buf);
    }
    if (report.contains("quality")) {
        const double minDihedral = report["quality"]["overall"]["min_dihedral_deg"]["min"].get<double>();
        const std::size_t below = report["quality"]["tets_below_min_dihedral"].get<std::size_t>();
        std::snprintf(buf, sizeof buf, "min dihedral %.2f deg; %zu tets below %.0f deg", minDihedral, below, o.minDihedralDeg);
        add("element quality", below == 0 ? "pass" : "warn", buf);
    }
    if (report.contains("distance") && !report["distance"].is_null()) {
        const Json& crowns = report["distance"]["summary"]["crowns"];
        if (crowns["domains"].get<int>() > 0) {
            const double h = crowns["hausdorff_mm"].get<double>();
            std::snprintf(buf, sizeof buf, "crown Hausdorff %.3f mm (limit %.3f; above the %.2f mm cervical band), mean %.4f mm",
                          h, o.crownToleranceMm, o.cervicalBandMm, crowns["mean_mm"].get<double>());
            add("crown shape", h <= o.crownToleranceMm ? "pass" : "warn", buf);
        }
    }
    if (report.contains("pdl_thickness") && !report["pdl_thickness"]["teeth"].empty()) {
        const bool judged = o.pdlTargetMm > 0;  // a PDL kept from a label map is measured only
        std::vector<std::string> off;
        for (const Json& t : report["pdl_thickness"]["teeth"]) {
            const int unn = t["tooth"].get<int>();
            const auto own = o.toothPdlTargetMm.find(unn);
            const double target = own != o.toothPdlTargetMm.end() ? own->second : o.pdlTargetMm;
            const double p05 = t["p05"].get<double>(), p95 = t["p95"].get<double>();
            if (target > 0 && (p05 < target - o.pdlToleranceMm || p95 > target + o.pdlToleranceMm))
                off.push_back(std::to_string(unn));
        }
        const Json& jaw = report["pdl_thickness"]["jaw"];
        std::snprintf(buf, sizeof buf, "median %.3f mm, p05-p95 %.3f-%.3f mm", jaw["median"].get<double>(), jaw["p05"].get<double>(),
                      jaw["p95"].get<double>());
        std::string detail = buf;
        if (judged) {
            std::snprintf(buf, sizeof buf, " (target %.3f +- %.3f)", o.pdlTargetMm, o.pdlToleranceMm);
            detail += buf;
        } else {
            detail += " (kept as segmented: measured, no target)";
        }
        for (const auto& [unn, target] : o.toothPdlTargetMm) {
            if (target > 0) std::snprintf(buf, sizeof buf, "; tooth %d edited to %.3f", unn, target);
            else std::snprintf(buf, sizeof buf, "; tooth %d edited to a profile: measured, no target", unn);
            detail += buf;
        }
        if (!off.empty()) {
            detail += "; outside on tooth";
            for (const auto& u : off) detail += " " + u;
        }
        add("PDL thickness", off.empty() ? "pass" : "warn", detail);
    }
    std::string status = "pass";
    for (const Json& c : checks) {
        if (c["status"] == "fail") status = "fail";
        else if (c["status"] == "warn" && status == "pass") status = "warn";
    }
    std::string line = status == "pass" ? "PASS" : status == "warn" ? "WARN" : "FAIL";
    for (const Json& c : checks) line += " | " + c["name"].get<std::string>() + ": " + c["detail"].get<std::string>();
    return {{"status", status}, {"line", line}, {"checks", checks}};
}

/// The "regions" rows (label, name, kind, tets, nodes, volume, surface size) and the "sizes" per kind
/// (regions, tets, nodes, surface and input surface sizes) of a valid mesh.
std::pair<Json, Json> regionsAndSizes(const TetMesh& mesh, const JawSurfaces* input, const ValidationReport& validation,
                                      std::map<Label, RegionBoundary>& boundaries) {
    // Nodes used per label and per kind, as flags over the node array (sets would cost seconds).
    std::map<Label, std::vector<char>> nodeUsed;
    std::map<Label, double> volumeOf;
    for (const auto& [label, count] : validation.tetsPerLabel) nodeUsed[label].assign(mesh.nodes.size(), 0);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& e = mesh.tets[t];
        auto& used = nodeUsed[mesh.labels[t]];
        for (std::int32_t v : e) used[static_cast<std::size_t>(v)] = 1;
        const Vec3& a = mesh.nodes[static_cast<std::size_t>(e[0])];
        volumeOf[mesh.labels[t]] += (mesh.nodes[static_cast<std::size_t>(e[1])] - a)
                                        .dot((mesh.nodes[static_cast<std::size_t>(e[2])] - a).cross(mesh.nodes[static_cast<std::size_t>(e[3])] - a)) / 6.0;
    }
    const auto countUsed = [](const std::vector<char>& used) { return static_cast<std::size_t>(std::count(used.begin(), used.end(), 1)); };
    Json regions = Json::array();
    Json sizes;
    std::map<std::string, std::vector<char>> nodeUsedByKind;
    for (const auto& [label, count] : validation.tetsPerLabel) {
        const std::string kind = kindName(labelKind(label));
        const SurfaceMesh& s = boundaries[label].surface;
        regions.push_back({{"label", label},
                           {"name", labelName(label)},
                           {"kind", kind},
                           {"tets", count},
                           {"nodes", countUsed(nodeUsed[label])},
                           {"volume_mm3", volumeOf[label]},
                           {"surface_vertices", usedVertexCount(s)},
                           {"surface_triangles", s.triangles.size()}});
        Json& k = sizes[kind];
        if (k.is_null()) k = Json::object();
        k["regions"] = k.value("regions", 0) + 1;
        k["volume_tets"] = k.value("volume_tets", std::size_t{0}) + count;
        k["surface_vertices"] = k.value("surface_vertices", std::size_t{0}) + usedVertexCount(s);
        k["surface_triangles"] = k.value("surface_triangles", std::size_t{0}) + s.triangles.size();
        auto& kindUsed = nodeUsedByKind[kind];
        kindUsed.resize(mesh.nodes.size(), 0);
        for (std::size_t v = 0; v < kindUsed.size(); ++v) kindUsed[v] |= nodeUsed[label][v];
    }
    for (auto& [kind, used] : nodeUsedByKind) sizes[kind]["volume_nodes"] = countUsed(used);
    if (input) {
        sizes["bone"]["input_vertices"] = usedVertexCount(input->bone);
        sizes["bone"]["input_triangles"] = input->bone.triangles.size();
        std::size_t v = 0, t = 0;
        for (const auto& [unn, s] : input->teeth) {
            v += usedVertexCount(s);
            t += s.triangles.size();
        }
        sizes["tooth"]["input_vertices"] = v;
        sizes["tooth"]["input_triangles"] = t;
    }
    return {regions, sizes};
}

/// PDL thickness per tooth and over the jaw (the "pdl_thickness" entry).
Json pdlThicknessReport(const std::map<Label, RegionBoundary>& boundaries, const EvalOptions& o, Progress& progress) {
    Json teeth = Json::array();
    std::vector<double> values, weights;
    for (const auto& [label, boundary] : boundaries) {
        if (labelKind(label) != LabelKind::Pdl) continue;
        const Label tooth = toothLabel(labelUnn(label));
        const SurfaceMesh toothSide = selectTriangles(boundary.surface, [&](std::size_t t) { return boundary.otherSide[t] == tooth; });
        const SurfaceMesh boneSide = selectTriangles(boundary.surface, [&](std::size_t t) {
            return boundary.otherSide[t] != kOutsideLabel && labelKind(boundary.otherSide[t]) == LabelKind::Bone;
        });
        if (toothSide.triangles.empty() || boneSide.triangles.empty()) continue;
        const PdlThickness th = pdlThickness(toothSide, boneSide, o.sampleSpacingMm, o.hausdorffToleranceMm, progress);
        Json row = toJson(th.summary);
        row["tooth"] = labelUnn(label);
        teeth.push_back(row);
        values.insert(values.end(), th.samples.distanceMm.begin(), th.samples.distanceMm.end());
        weights.insert(weights.end(), th.samples.weightMm2.begin(), th.samples.weightMm2.end());
    }
    Json pdl;
    pdl["target_mm"] = o.pdlTargetMm;
    pdl["teeth"] = teeth;
    if (!teeth.empty()) {
        Json jaw = toJson(summarizeWeighted(values, weights));
        double maxMm = 0;  // the refined per-tooth maxima bound the jaw's
        for (const Json& t : teeth) maxMm = std::max(maxMm, t["max"].get<double>());
        jaw["max"] = maxMm;
        pdl["jaw"] = jaw;
        const double hi = std::max({2.0 * o.pdlTargetMm, o.pdlTargetMm > 0 ? 0.0 : maxMm, 1e-3});
        pdl["histogram"] = {{"lo", 0.0}, {"hi", hi}, {"bins", o.histogramBins}, {"weights_mm2", weightedHistogram(values, weights, 0.0, hi, o.histogramBins)}};
    }
    return pdl;
}

/// One region's two-sided distances to its input surface (a tooth's crown, root and cervical band;
/// the bone's outer surface and socket); null when it has no input surface to compare with.
Json domainDistances(const JawSurfaces& input, Label label, const RegionBoundary& boundary, const EvalOptions& o,
                     Progress& progress) {
    const LabelKind kind = labelKind(label);
    if (kind == LabelKind::Tooth) {
        const auto in = input.teeth.find(labelUnn(label));
        if (in == input.teeth.end() || in->second.triangles.empty()) return nullptr;
        Json d = {{"name", labelName(label)}, {"label", label}, {"kind", "tooth"}};
        d["parts"] = twoSidedDistances(boundary.surface, toothParts(boundary, o.cervicalBandMm), in->second,
                                       {"crown", "root", "cervical"}, o, progress);
        return d;
    }
    if (kind == LabelKind::Bone && !input.bone.triangles.empty()) {
        std::vector<int> part(boundary.otherSide.size());
        for (std::size_t t = 0; t < part.size(); ++t) part[t] = boundary.otherSide[t] == kOutsideLabel ? 0 : 1;
        Json d = {{"name", labelName(label)}, {"label", label}, {"kind", "bone"}};
        d["parts"] = twoSidedDistances(boundary.surface, part, input.bone, {"outer", "socket"}, o, progress);
        return d;
    }
    return nullptr;
}

/// Distances from the mesh's region surfaces to the input surfaces, per tooth (crown, root) and for the
/// bone (outer, socket), with their summary (the "distance" entry).
Json distanceReport(const JawSurfaces& input, const std::map<Label, RegionBoundary>& boundaries, const EvalOptions& o,
                    Progress& progress) {
    // The domains at once (each is parallel inside, but its trees are built serially), in the
    // order of their labels in the report; each depends on its own surfaces alone.
    std::vector<std::pair<Label, const RegionBoundary*>> regions;
    for (const auto& [label, boundary] : boundaries) regions.emplace_back(label, &boundary);
    std::vector<Json> measured(regions.size());
    CancelOnlyProgress quiet(progress);
    parallelForFirstErrorInOrder(regions.size(), progress, [&](std::size_t i) {
        measured[i] = domainDistances(input, regions[i].first, *regions[i].second, o, quiet);
    });
    Json domains = Json::array();
    for (Json& d : measured)
        if (!d.is_null()) domains.push_back(std::move(d));
    Json distance;
    distance["domains"] = domains;
    distance["summary"] = {{"crowns", aggregateParts(domains, "tooth", "crown")},
                           {"cervical_bands", aggregateParts(domains, "tooth", "cervical")},
                           {"roots", aggregateParts(domains, "tooth", "root")},
                           {"bone_outer", aggregateParts(domains, "bone", "outer")},
                           {"bone_socket", aggregateParts(domains, "bone", "socket")}};
    return distance;
}

}  // namespace

nlohmann::json evaluateMesh(const TetMesh& mesh, const JawSurfaces* input, const EvalOptions& o, Progress& progress) {
    const auto start = std::chrono::steady_clock::now();
    Json report;
    report["schema"] = "jawmesh-eval/1";
    report["options"] = {{"sample_spacing_mm", o.sampleSpacingMm}, {"hausdorff_tolerance_mm", o.hausdorffToleranceMm},
                         {"pdl_target_mm", o.pdlTargetMm},        {"pdl_tolerance_mm", o.pdlToleranceMm},
                         {"crown_tolerance_mm", o.crownToleranceMm}, {"cervical_band_mm", o.cervicalBandMm},
                         {"min_dihedral_deg", o.minDihedralDeg}};
    for (const auto& [unn, target] : o.toothPdlTargetMm) report["options"]["tooth_pdl_target_mm"][std::to_string(unn)] = target;
    if (!o.edits.is_null()) report["edits"] = o.edits;
    report["mesh"] = {{"nodes", mesh.nodes.size()}, {"tets", mesh.tets.size()}};

    std::vector<int> inputTeeth;
    if (input)
        for (const auto& [unn, surface] : input->teeth) inputTeeth.push_back(unn);
    ValidationReport validation;
    {
        ProgressStage stage(progress, "eval: validate");
        validation = validateTetMesh(mesh, inputTeeth);
    }
    report["validation"] = toJson(validation);
    if (validation.badIndices || validation.unknownLabels || validation.sizeMismatch || mesh.tets.empty()) {
        report["distance"] = nullptr;
        report["verdict"] = verdict(report, o);
        return report;
    }

    // Regions, their boundaries and sizes.
    std::map<Label, RegionBoundary> boundaries;
    {
        ProgressStage stage(progress, "eval: region surfaces");
        boundaries = regionBoundaries(mesh);
    }
    Json regions, sizes;
    std::tie(regions, sizes) = regionsAndSizes(mesh, input, validation, boundaries);

    {
        ProgressStage stage(progress, "eval: element quality");
        report["quality"] = qualityJson(mesh, tetShapes(mesh), o, regions);
    }
    report["regions"] = regions;
    report["sizes"] = sizes;

    {
        ProgressStage stage(progress, "eval: PDL thickness");
        report["pdl_thickness"] = pdlThicknessReport(boundaries, o, progress);
    }

    // Distances to the input surfaces.
    if (input) requireInputOverlapsMesh(mesh, *input);
    if (!input) {
        report["distance"] = nullptr;
    } else {
        ProgressStage stage(progress, "eval: distance to input");
        report["distance"] = distanceReport(*input, boundaries, o, progress);
    }
    report["verdict"] = verdict(report, o);
    report["seconds"] = secondsSince(start);
    return report;
}

}  // namespace jawmesh
