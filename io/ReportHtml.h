// report.html: the evaluation report (report.json's content, tet/EvaluateMesh.h) as one
// self-contained page: verdict, tables, histograms (inline SVG) and cross-section pictures
// (embedded PNG data URIs). Everything on the page is read from the JSON, so the page and the
// numbers can never disagree.
#pragma once

#include "io/Labels.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace jawmesh {

/// A picture for the page: PNG file bytes and a caption.
struct ReportPicture {
    std::string id;       ///< HTML id, e.g. "section-tooth-24"
    std::string caption;
    std::string png;      ///< PNG bytes (io/PngWriter.h)
};

/// RGB colour of a label in the pictures and legends: bone beige, teeth in shades of blue
/// (neighbours differ), PDL red, outside white.
std::array<std::uint8_t, 3> labelColour(Label label);

/// The page. `title` heads it (e.g. the mesh path). Cost: O(size of the JSON and pictures).
/// Throws nlohmann::json exceptions only for a report that does not follow the schema.
std::string reportHtml(const nlohmann::json& report, const std::vector<ReportPicture>& pictures, const std::string& title);

}  // namespace jawmesh
