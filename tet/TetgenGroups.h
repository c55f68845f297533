// TetGen on two groups of regions at once. With the boundary preserved (-Y) TetGen puts no point on
// an input triangle, so the regions on either side of an interface can be meshed by separate runs
// and their tets still share every face of it: the union is the mesh of one run (conformal by
// construction), made in about the time of the larger group. The groups are balanced by the
// regions' interface triangles (any split of the regions is conformal). One group runs in a child process (io/ChildProcess.h: TetGen's predicates keep
// global state set from each run's bounding box, so two runs may not share a process), the
// other in this one; both in children when the caller isolates TetGen.
#pragma once

#include "tet/TetgenAdapter.h"

#include <cstdint>
#include <map>

namespace jawmesh {

/// The group (0 or 1) each region of `plc` is meshed in, by label: the labels, largest first by
/// their interface triangles (the run's cost follows them), each to the group with fewer so far.
std::map<Label, int> tetgenGroups(const InterfaceComplex& plc);

/// runTetgen on `plc` by groups (file comment), in parallel when the task arena has more than one
/// thread (the same mesh either way): nodes are plc's points (in order), then each group's
/// Steiner points, group 0 first; every tet is labeled from the interface sides
/// (tet/LabelFromSides.h) and kept by the group its label belongs to (a region no seed of the
/// group reached is the other group's, or outside). With a group empty, one run as runTetgen
/// (runTetgenInChild when isolated), its tets labeled from the sides too; without the boundary
/// preserved, that one run with TetGen's own labels. childPeakBytes is raised to the peak
/// resident memory of the children. Throws what runTetgen and labelFromSides throw.
TetgenMesh runTetgenInGroups(const InterfaceComplex& plc, const TetgenRun& run, bool preserveBoundary, bool isolated,
                             std::uint64_t& childPeakBytes);

}  // namespace jawmesh
