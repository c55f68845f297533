// Tooth axes in the Open-Full-Jaw JSON shape: per UNN {"c": crown centre, "x", "y", "z": end points
// of the unit mesial-distal, labial and occlusal (long) axes drawn from c}. All in mm.
#pragma once

#include "io/SurfaceMesh.h"

#include <map>
#include <string>

namespace jawmesh {

struct ToothAxes {
    Vec3 crownCentre = Vec3::Zero();   ///< "c", mm
    Vec3 mesialDistal = Vec3::UnitX(); ///< unit; "x" end point = c + mesialDistal
    Vec3 labial = Vec3::UnitY();       ///< unit; "y" end point = c + labial
    Vec3 occlusal = Vec3::UnitZ();     ///< unit, long axis toward the crown; "z" end point = c + occlusal
};

/// Reads a teeth_axes_<jaw>.json; end points are turned into unit vectors from c.
/// Throws Error naming the file for malformed JSON, missing keys, non-numeric or zero-length axes.
std::map<int, ToothAxes> readToothAxes(const std::string& path);

/// readToothAxes on JSON text held in memory; `name` names it in messages. Throws as readToothAxes.
std::map<int, ToothAxes> parseToothAxes(const std::string& text, const std::string& name);

/// Writes the same shape (atomically).
void writeToothAxes(const std::map<int, ToothAxes>& axes, const std::string& path);

}  // namespace jawmesh
