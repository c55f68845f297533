// The TetGen 1.5 adapter: an interface complex goes in as tetgenio (its triangles as marked facets,
// its seeds as regions), one tetrahedralize call runs under a switch string, and the output comes
// back as plain data (nodes, positively oriented tets labeled from the seeds, TetGen's subfaces).
// runTetgenInChild makes the same call in a child process (io/ChildProcess.h). Which switches to
// try, and in which order, is tet/Tetrahedralize.cpp's business.
#pragma once

#include "io/ChildProcess.h"
#include "io/InterfaceComplex.h"
#include "io/TetMesh.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace jawmesh {

/// TetGen 1.5's own target for the largest dihedral angle of its optimisation, degrees.
constexpr double kTetgenDefaultOptMaxDihedralDeg = 165.0;

/// One TetGen run: its switches and what they cannot say.
struct TetgenRun {
    std::string switches;  ///< TetGen's command-line switches, e.g. "pzQAq1.5/10aYMO3/7"
    /// Target of TetGen's optimisation for the largest dihedral angle (no switch sets it), degrees.
    double optMaxDihedralDeg = kTetgenDefaultOptMaxDihedralDeg;
    /// Per seed of the complex, the volume bound of its region (used with -a), mm^3; <= 0: none.
    std::vector<double> seedVolumeBoundsMm3;
};

/// TetGen's result as plain data.
struct TetgenMesh {
    /// Its nodes (the input points first, in order, when -z keeps the numbering), its tets oriented
    /// positively, and per tet the label of the seed whose region it is in (kOutsideLabel where
    /// no seed reached, or without -A).
    TetMesh mesh;
    /// TetGen's subfaces as sorted node triples, sorted: the input triangles, and their pieces
    /// where TetGen had to split one (despite -Y).
    std::vector<std::array<std::int32_t, 3>> facets;
};

/// A number as written in TetGen's switches (and in the stage's messages): printf's %.9g.
std::string tetgenNumber(double v);

/// Tetrahedralizes `plc` with TetGen under run.switches: every interface triangle is a facet
/// (marker = interfaceMarker of its sides), each seed a region (attribute = its index + 1, not its
/// label: TetGen numbers the regions no seed reaches after the largest attribute).
/// Throws Error ("tetrahedralize: <reason>") when TetGen rejects the switches, fails (out of memory,
/// intersecting or too close facets, features below its tolerance...) or makes no tetrahedra.
/// Not every failure is a throw: TetGen 1.5.0 aborts on some inputs (see runTetgenInChild).
/// Cost: TetGen's, roughly O(n log n) in the output size; single-threaded, deterministic.
TetgenMesh runTetgen(const InterfaceComplex& plc, const TetgenRun& run);

/// runTetgen in a child process (runForked): TetGen 1.5.0 aborts on some inputs (failed assertions
/// in its facet recovery, seen on a locally refined mandible surface) where it should throw, and
/// an abort must not take the run down. The mesh comes back through a pipe; childPeakBytes is
/// raised to the child's peak resident memory. Throws what runTetgen throws, and Error when the
/// child cannot be started, dies or fails.
TetgenMesh runTetgenInChild(const InterfaceComplex& plc, const TetgenRun& run, std::uint64_t& childPeakBytes);

/// runTetgenInChild in two halves (startForked, finishForked), for a run in this process while the
/// child's goes on. start throws Error when no child could be started (no pipe or no fork: out of
/// processes or memory), TetGen not run at all; finish throws what runTetgenInChild throws.
ForkedChild startTetgenInChild(const InterfaceComplex& plc, const TetgenRun& run);
TetgenMesh finishTetgenInChild(ForkedChild& child, const TetgenRun& run, std::uint64_t& childPeakBytes);

}  // namespace jawmesh
