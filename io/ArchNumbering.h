// Numbering the teeth of one combined mesh (an all_teeth.obj) along the dental arch: split into
// teeth, find the occlusal side and the midline, and give each tooth its Universal number. Kept
// beside the case reader (io/Case.h, loadJaw) because every stage reads its case through it; it
// uses no other stage.
#pragma once

#include "io/Labels.h"
#include "io/SurfaceMesh.h"

#include <map>
#include <string>
#include <vector>

namespace jawmesh {

/// Splits a mesh holding several teeth into teeth and gives each its UNN by position along the arch.
/// Rule: components are triangles connected through shared vertices (positions welded first);
/// a component whose bounding box lies inside another's (a pulp shell) joins that one; components
/// whose bounding-box diagonal is below 20% of the median component's are specks and are dropped
/// (noted). The occlusal plane is the
/// least-squares plane of the tooth centroids; the occlusal side is where the crowns stick out of
/// the bone (tooth centroid versus the bone vertices around it), or +z (mandible) / -z (maxilla)
/// when no bone is near. Teeth are ordered by angle around the mean centroid, the arch's open end
/// at the largest angular gap; anterior points from the middle of the two end teeth to the mean
/// centroid, patient-left = superior x anterior. The midline lies between the two adjacent teeth
/// whose midpoint is most anterior (the central incisors), and each side is numbered outward
/// from it: mandible left 24, 23, ... 17 and right 25, 26, ... 32; maxilla right 8, 7, ... 1 and
/// left 9, 10, ... 16 (so missing teeth are assumed at the back of the arch).
/// @param allTeeth  the combined teeth, mm
/// @param jaw       which numbering to use
/// @param bone      the jaw's bone (may be empty), used only to tell crowns from roots
/// @param notes     receives one line describing the numbering (may be null)
/// Throws Error when there is no component or more than 8 teeth on one side. Cost: O(n log n).
std::map<int, SurfaceMesh> numberTeethAlongArch(const SurfaceMesh& allTeeth, Jaw jaw, const SurfaceMesh& bone,
                                                std::vector<std::string>* notes = nullptr);

}  // namespace jawmesh
