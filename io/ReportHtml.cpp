// Implements io/ReportHtml.h; what it computes, its rules and its contract are documented there.
#include "io/ReportHtml.h"

#include "io/PngWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace jawmesh {
namespace {

using Json = nlohmann::json;

const char* kKindColour[][2] = {{"bone", "#b8893a"}, {"tooth", "#3f6fc4"}, {"pdl", "#d03a3a"}};

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

/// A number for a table cell: null (infinite) as "inf", integers as such, else `digits` decimals.
std::string cell(const Json& v, int digits = 3) {
    if (v.is_null()) return "inf";
    if (v.is_number_integer() || v.is_number_unsigned()) return std::to_string(v.get<long long>());
    if (v.is_number()) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.*f", digits, v.get<double>());
        return buf;
    }
    if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
    return escape(v.is_string() ? v.get<std::string>() : v.dump());
}

std::string row(const std::vector<std::string>& cells, bool header = false) {
    std::string r = "<tr>";
    for (const auto& c : cells) r += (header ? "<th>" : "<td>") + c + (header ? "</th>" : "</td>");
    return r + "</tr>\n";
}

/// Step histogram of several series over [lo, hi) as inline SVG, each series normalised to its own
/// total (so a small PDL shows next to a large bone).
std::string histogramSvg(const std::string& id, const std::string& title, double lo, double hi,
                         const std::vector<std::pair<std::string, std::vector<double>>>& series, const std::string& unit) {
    const double w = 440, h = 230, left = 45, right = 10, top = 24, bottom = 40;
    const double pw = w - left - right, ph = h - top - bottom;
    double peak = 0;
    for (const auto& [name, counts] : series) {
        double total = 0;
        for (double c : counts) total += c;
        for (double c : counts) peak = std::max(peak, total > 0 ? c / total : 0.0);
    }
    if (peak <= 0) peak = 1;
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(1);
    s << "<figure class=\"hist\"><svg id=\"" << id << "\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h
      << "\" viewBox=\"0 0 " << w << ' ' << h << "\">\n"
      << "<rect x=\"0\" y=\"0\" width=\"" << w << "\" height=\"" << h << "\" fill=\"#fff\"/>\n"
      << "<text x=\"" << left << "\" y=\"16\" font-size=\"13\" font-family=\"sans-serif\">" << escape(title) << "</text>\n"
      << "<line x1=\"" << left << "\" y1=\"" << top + ph << "\" x2=\"" << left + pw << "\" y2=\"" << top + ph << "\" stroke=\"#333\"/>\n"
      << "<line x1=\"" << left << "\" y1=\"" << top << "\" x2=\"" << left << "\" y2=\"" << top + ph << "\" stroke=\"#333\"/>\n";
    char lab[64];
    for (int k = 0; k <= 4; ++k) {
        const double x = left + pw * k / 4.0;
        std::snprintf(lab, sizeof lab, "%.3g", lo + (hi - lo) * k / 4.0);
        s << "<text x=\"" << x << "\" y=\"" << top + ph + 14 << "\" font-size=\"10\" text-anchor=\"middle\" font-family=\"sans-serif\">"
          << lab << "</text>\n";
    }
    std::snprintf(lab, sizeof lab, "%.0f%%", 100 * peak);
    s << "<text x=\"" << left - 4 << "\" y=\"" << top + 8 << "\" font-size=\"10\" text-anchor=\"end\" font-family=\"sans-serif\">" << lab
      << "</text>\n<text x=\"" << left + pw / 2 << "\" y=\"" << h - 6
      << "\" font-size=\"11\" text-anchor=\"middle\" font-family=\"sans-serif\">" << escape(unit) << "</text>\n";
    int legend = 0;
    for (const auto& [name, counts] : series) {
        std::string colour = "#555";
        for (const auto& kc : kKindColour)
            if (name == kc[0]) colour = kc[1];
        double total = 0;
        for (double c : counts) total += c;
        if (counts.empty() || total <= 0) continue;
        s << "<path fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.6\" d=\"M" << left << ' ' << top + ph;
        const double bw = pw / static_cast<double>(counts.size());
        for (std::size_t b = 0; b < counts.size(); ++b) {
            const double y = top + ph - ph * (counts[b] / total) / peak;
            s << " L" << left + bw * static_cast<double>(b) << ' ' << y << " L" << left + bw * static_cast<double>(b + 1) << ' ' << y;
        }
        s << " L" << left + pw << ' ' << top + ph << "\"/>\n";
        s << "<text x=\"" << left + pw - 4 << "\" y=\"" << top + 12 + 13 * legend++ << "\" font-size=\"11\" text-anchor=\"end\" fill=\""
          << colour << "\" font-family=\"sans-serif\">" << escape(name) << "</text>\n";
    }
    s << "</svg></figure>\n";
    return s.str();
}

std::string sizesTable(const Json& report) {
    std::string t = "<table id=\"sizes\">\n" +
                    row({"region kind", "regions", "input vertices", "input triangles", "output surface vertices",
                         "output surface triangles", "output volume nodes", "output volume tets"},
                        true);
    for (const char* kind : {"bone", "tooth", "pdl"}) {
        if (!report["sizes"].contains(kind)) continue;
        const Json& k = report["sizes"][kind];
        const auto get = [&](const char* key) { return k.contains(key) ? cell(k[key]) : std::string("&ndash;"); };
        t += row({kind, get("regions"), get("input_vertices"), get("input_triangles"), get("surface_vertices"),
                  get("surface_triangles"), get("volume_nodes"), get("volume_tets")});
    }
    return t + "</table>\n";
}

std::string regionsTable(const Json& report) {
    std::string t = "<table id=\"regions\">\n" +
                    row({"label", "region", "tets", "nodes", "volume mm&sup3;", "min radius ratio", "min volume-edge ratio",
                         "max radius-edge ratio", "min dihedral &deg;", "max dihedral &deg;"},
                        true);
    for (const Json& r : report["regions"]) {
        const Json& q = r["quality"];
        t += row({cell(r["label"]), cell(r["name"]), cell(r["tets"]), cell(r["nodes"]), cell(r["volume_mm3"], 2),
                  cell(q["radius_ratio"]["min"]), cell(q["volume_edge_ratio"]["min"]), cell(q["radius_edge_ratio"]["max"], 2),
                  cell(q["min_dihedral_deg"]["min"], 2), cell(q["max_dihedral_deg"]["max"], 2)});
    }
    return t + "</table>\n";
}

std::string distanceTable(const Json& report) {
    const Json& d = report["distance"];
    std::string t = "<table id=\"hausdorff\">\n" +
                    row({"domain", "part", "Hausdorff mm (two-sided)", "mean mm (two-sided)", "output&rarr;input max", "output&rarr;input mean",
                         "output&rarr;input p95", "input&rarr;output max", "input&rarr;output mean", "area mm&sup2; (output)"},
                        true);
    for (const char* name : {"crowns", "cervical_bands", "roots", "bone_outer", "bone_socket"}) {
        const Json& s = d["summary"][name];
        if (!s.is_object() || s["domains"].get<int>() == 0) continue;
        t += "<tr class=\"summary\"><td>all " + std::string(name) + "</td><td></td><td>" + cell(s["hausdorff_mm"]) + "</td><td>" +
             cell(s["mean_mm"], 4) + "</td><td colspan=\"6\"></td></tr>\n";
    }
    for (const Json& dom : d["domains"])
        for (const auto& [part, p] : dom["parts"].items()) {
            if (part == "whole" || !p["present"].get<bool>()) continue;
            t += row({cell(dom["name"]), part, cell(p["hausdorff_mm"]), cell(p["mean_mm"], 4), cell(p["output_to_input"]["max"]),
                      cell(p["output_to_input"]["mean"], 4), cell(p["output_to_input"]["p95"]), cell(p["input_to_output"]["max"]),
                      cell(p["input_to_output"]["mean"], 4), cell(p["output_to_input"]["area_mm2"], 1)});
        }
    return t + "</table>\n";
}

std::string pdlTable(const Json& pdl) {
    std::string t = "<table id=\"pdl\">\n" + row({"tooth", "min", "p05", "median", "p95", "mean", "max", "area mm&sup2;"}, true);
    for (const Json& r : pdl["teeth"])
        t += row({cell(r["tooth"]), cell(r["min"]), cell(r["p05"]), cell(r["median"]), cell(r["p95"]), cell(r["mean"]), cell(r["max"]),
                  cell(r["area_mm2"], 1)});
    if (pdl.contains("jaw")) {
        const Json& j = pdl["jaw"];
        t += "<tr class=\"summary\">" + std::string("<td>jaw</td><td>") + cell(j["min"]) + "</td><td>" + cell(j["p05"]) + "</td><td>" +
             cell(j["median"]) + "</td><td>" + cell(j["p95"]) + "</td><td>" + cell(j["mean"]) + "</td><td>" + cell(j["max"]) +
             "</td><td>" + cell(j["weight"], 1) + "</td></tr>\n";
    }
    return t + "</table>\n";
}

std::string legend(const Json& report) {
    std::string s = "<p class=\"legend\">";
    for (const Json& r : report["regions"]) {
        const auto c = labelColour(r["label"].get<Label>());
        char hex[8];
        std::snprintf(hex, sizeof hex, "#%02x%02x%02x", c[0], c[1], c[2]);
        s += "<span><i style=\"background:" + std::string(hex) + "\"></i>" + escape(r["name"].get<std::string>()) + "</span> ";
    }
    return s + "</p>\n";
}

}  // namespace

std::array<std::uint8_t, 3> labelColour(Label label) {
    switch (labelKind(label)) {
    case LabelKind::Bone: return {222, 196, 140};
    case LabelKind::Pdl: return {214, 48, 48};
    case LabelKind::Implant: return {140, 140, 150};  // titanium grey
    case LabelKind::Tooth: {
        static const std::array<std::uint8_t, 3> shades[] = {{150, 190, 240}, {95, 140, 215}, {185, 215, 250}, {120, 165, 230}};
        return shades[labelUnn(label) % 4];
    }
    default: return {255, 255, 255};
    }
}

std::string reportHtml(const Json& report, const std::vector<ReportPicture>& pictures, const std::string& title) {
    const Json& verdict = report["verdict"];
    const std::string status = verdict["status"].get<std::string>();
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>jawmesh evaluation: " << escape(title) << "</title>\n"
      << "<style>body{font-family:sans-serif;margin:24px;color:#222;max-width:1400px}"
         "table{border-collapse:collapse;margin:8px 0 20px}td,th{border:1px solid #bbb;padding:3px 8px;text-align:right;font-size:13px}"
         "th{background:#eee}td:first-child,td:nth-child(2){text-align:left}tr.summary td{font-weight:bold;background:#f6f6f6}"
         "#verdict{padding:10px 14px;font-size:15px;border-radius:4px;font-weight:bold}"
         ".pass{background:#d9f2d9;border:2px solid #3a3}.warn{background:#fff1cc;border:2px solid #d90}.fail{background:#fdd;border:2px solid #c33}"
         "figure{display:inline-block;margin:6px;vertical-align:top}figcaption{font-size:12px;max-width:600px}"
         "figure img{border:1px solid #999;max-width:100%}.legend span{margin-right:12px;font-size:13px}"
         ".legend i{display:inline-block;width:12px;height:12px;margin-right:4px;border:1px solid #777}</style></head><body>\n"
      << "<h1>jawmesh evaluation</h1>\n<p>" << escape(title) << "</p>\n"
      << "<p id=\"verdict\" class=\"" << escape(status) << "\">" << escape(verdict["line"].get<std::string>()) << "</p>\n";
    h << "<table id=\"checks\">\n" << row({"check", "status", "detail"}, true);
    for (const Json& c : verdict["checks"]) h << row({cell(c["name"]), cell(c["status"]), cell(c["detail"])});
    h << "</table>\n";
    if (report.contains("edits")) {
        // What-ifs (levelset/JawEdits.h): the distances to the input differ where they changed it.
        h << "<h2>Edits</h2>\n<p>Applied in order before carving; where they changed the anatomy the distance to the "
             "input differs by design.</p>\n<table>\n"
          << row({"file", "op", "edit and what it measured (mm)"}, true);
        for (const Json& record : report["edits"])
            for (Json e : record["applied"]) {
                const std::string op = e["op"].get<std::string>();
                for (const char* key : {"op", "axis", "side_direction", "seconds"}) e.erase(key);
                if (e.contains("teeth") && e["teeth"].is_array())
                    for (Json& t : e["teeth"])
                        if (t.is_object()) t.erase("axis");
                h << row({escape(record["file"].get<std::string>()), escape(op), escape(e.dump())});
            }
        h << "</table>\n";
    }
    if (!report.contains("regions")) return h.str() + "<p>The mesh is structurally broken; see report.json.</p></body></html>\n";

    h << "<h2>Mesh sizes</h2>\n" << sizesTable(report);
    h << "<h2>Regions</h2>\n" << regionsTable(report);
    if (!report["distance"].is_null()) {
        h << "<h2>Distance to the input surfaces</h2>\n<p>Crown: tooth faces against the outside; root: against PDL or bone "
             "(the crest is where they meet); cervical: the crown faces within "
          << cell(report["options"].value("cervical_band_mm", 0.0)) << " mm of the root, where the root's erosion begins. Area samples every "
          << cell(report["options"]["sample_spacing_mm"]) << " mm; maxima exact to " << cell(report["options"]["hausdorff_tolerance_mm"], 4)
          << " mm.</p>\n"
          << distanceTable(report);
    } else {
        h << "<h2>Distance to the input surfaces</h2>\n<p>No input given (<code>--input</code>).</p>\n";
    }
    const Json& pdl = report["pdl_thickness"];
    h << "<h2>PDL thickness (mm)</h2>\n<p>Distance from each point of the tooth-side PDL interface to the bone-side interface, "
         "area-weighted; target "
      << cell(pdl["target_mm"]) << " mm.</p>\n"
      << pdlTable(pdl);

    h << "<h2>Histograms</h2>\n";
    const Json& hist = report["quality"]["histograms"];
    const std::pair<const char*, const char*> measures[] = {{"radius_ratio", "radius ratio 3r/R (regular 1)"},
                                                            {"volume_edge_ratio", "volume-edge ratio (regular 1)"},
                                                            {"radius_edge_ratio", "radius-edge ratio R/l_min (regular 0.612)"},
                                                            {"min_dihedral_deg", "minimum dihedral angle (deg)"},
                                                            {"max_dihedral_deg", "maximum dihedral angle (deg)"}};
    for (const auto& [key, label] : measures) {
        const Json& m = hist[key];
        std::vector<std::pair<std::string, std::vector<double>>> series;
        for (const auto& [kind, counts] : m["counts"].items()) series.emplace_back(kind, counts.get<std::vector<double>>());
        h << histogramSvg(std::string("hist-") + key, std::string(label) + ", fraction of tets per kind", m["lo"].get<double>(),
                          m["hi"].get<double>(), series, label);
    }
    if (pdl.contains("histogram"))
        h << histogramSvg("hist-pdl-thickness", "PDL thickness, fraction of area", pdl["histogram"]["lo"].get<double>(),
                          pdl["histogram"]["hi"].get<double>(), {{"pdl", pdl["histogram"]["weights_mm2"].get<std::vector<double>>()}}, "mm");

    h << "<h2>Cross-sections</h2>\n" << legend(report);
    for (const ReportPicture& p : pictures)
        h << "<figure><img id=\"" << escape(p.id) << "\" alt=\"" << escape(p.caption) << "\" src=\"data:image/png;base64," << base64(p.png)
          << "\"><figcaption>" << escape(p.caption) << "</figcaption></figure>\n";
    h << "</body></html>\n";
    return h.str();
}

}  // namespace jawmesh
