// Label-map cases for the run tests (issue #23): the surfaces a label volume's voxels give, written
// as a surface case's input folder so that support_RunChecks.h can measure a run against them.
#pragma once

#include "io/TetMesh.h"

#include <string>

namespace jawmesh::test {

/// The volume of every tet of the mesh, mm^3 (the sum of tet/ElementQuality.h's labelVolumesMm3).
double totalVolumeMm3(const TetMesh& mesh);

/// Reads <labelJawDir>/labels.<ext> and its labels.json (jaw from the folder name), and writes
/// the bone and tooth surfaces the pipeline makes of them to <outJawDir>/bone/<jaw>.stl and
/// <outJawDir>/teeth/tooth_<UNN>.stl.
void writeLabelSurfaces(const std::string& labelJawDir, const std::string& outJawDir);

}  // namespace jawmesh::test
