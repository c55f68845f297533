// Hole repair of an interface complex before TetGen: a complex with a hole meshes as readily as a
// closed one, and its regions then run into each other through the hole. Local triangulations
// close what they can (filters/FillSurfaceHoles.h); what they leave is patched with the faces of a
// quick tetrahedralization (tet/HoleCut.h), when that patch stays near the holes.
#pragma once

#include "io/InterfaceComplex.h"
#include "tet/Tetrahedralize.h"

#include <vector>

namespace jawmesh {

/// Closes the holes of `input` into `repaired`: local triangulations (filters/FillSurfaceHoles.h),
/// pass after pass while a pass closes something, at most kHoleRepairPasses; then, for what is
/// left, a patch of tet faces (a TetGen run in a child process, tet/HoleCut.h), taken only when each
/// of its faces lies within kHoleBallPerDiameter hole diameters of a hole's centre. A hole is a
/// local defect of a surface that took most of the run to make.
/// Returns the complex to mesh: `input` itself when it has no hole, else `repaired` (which may
/// still have holes: tetrahedralize names them). seedVolumeBoundsMm3 is TetgenRun's, per seed of
/// `input`. Records in stats.holeRepair what was closed and left, in stats.failedAttempts the patch
/// runs that failed (TetGen's errors are not thrown), in stats.childPeakMemoryBytes their memory.
/// Cost: a pass is linear in the surface; a patch is a TetGen run without quality bound.
const InterfaceComplex& repairHoles(const InterfaceComplex& input, InterfaceComplex& repaired,
                                    const std::vector<double>& seedVolumeBoundsMm3, TetStats& stats);

constexpr int kHoleRepairPasses = 3;
/// The radius of the ball around a hole's centre that its patch must stay in, in hole diameters.
constexpr double kHoleBallPerDiameter = 1.5;

}  // namespace jawmesh
