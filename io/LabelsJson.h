// labels.json next to every volume mesh: what each label number means, identical for all formats.
#pragma once

#include "io/Labels.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace jawmesh {

/// {"labels": {"1": {"kind": "bone", "name": "bone_mandible"},
///             "124": {"kind": "tooth", "tooth": 24, "name": "tooth_24"},
///             "224": {"kind": "pdl", "tooth": 24, "name": "pdl_24"}}}
/// for the distinct labels given (duplicates ignored, keys in increasing numeric order; bone kinds
/// also carry "jaw": "mandible" | "maxilla"). Throws Error for 0 or unknown labels. Cost: O(n log n).
nlohmann::ordered_json labelsJson(const std::vector<Label>& labels);

/// Writes labelsJson(labels) to `path` atomically (2-space indent). Throws Error on I/O failure.
void writeLabelsJson(const std::vector<Label>& labels, const std::string& path);

}  // namespace jawmesh
