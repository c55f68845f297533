// Label-map cases for the run tests (issue #23): the surfaces a label volume's voxels give, written
// as a surface case's input folder so that support_RunChecks.h can measure a run against them.
#pragma once

#include "io/Labels.h"
#include "io/TetMesh.h"

#include <map>
#include <string>

namespace jawmesh::test {

/// The volume of every tet of the mesh, mm^3 (the sum of tet/ElementQuality.h's labelVolumesMm3).
double totalVolumeMm3(const TetMesh& mesh);

/// The volume (mm^3) of the voxels of every mesh label (bone, tooth_<UNN>, pdl_<UNN>) in
/// <labelJawDir>/labels.<ext>, named through its labels.json when it has one.
std::map<Label, double> labelledVolumesMm3(const std::string& labelJawDir);

/// Reads <labelJawDir>/labels.<ext> and its labels.json (jaw from the folder name), and writes
/// the bone and tooth surfaces the pipeline makes of them to <outJawDir>/bone/<jaw>.stl and
/// <outJawDir>/teeth/tooth_<UNN>.stl.
void writeLabelSurfaces(const std::string& labelJawDir, const std::string& outJawDir);

}  // namespace jawmesh::test
