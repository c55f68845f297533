// Local repair of an interface complex with holes (issue #27): each hole's boundary loop
// (filters/HoleLoops.h) is closed by a patch of triangles of the sheet it lies in, checked exactly
// against the surface around it. The holes this is for are small and mostly flat: whole tile faces
// the extraction once missed (docs/DESIGN.md, Known pitfalls), 0.4-5 mm across.
#pragma once

#include "io/InterfaceComplex.h"

#include <nlohmann/json.hpp>

#include <array>
#include <vector>

namespace jawmesh {

enum class HoleRepair {
    EarClipping,  ///< a patch over the loop, by ear clipping in its plane
    MinimumArea,  ///< a patch over the loop, its triangulation of least area (a loop that is not flat)
    CentroidFan,  ///< a patch over the loop, a fan from an added vertex at its centroid
    RaisedFan,    ///< the same fan with its apex moved along the loop's normal, to open a sharp wedge
    TetCut,       ///< a patch of tet faces, cut from a tetrahedralization of the open complex (tet/HoleCut.h)
    LidRemoved,   ///< the loop was the rim of a lid (filters/HoleFlap.h), which was taken out
};

/// What a HoleRepair is called in run.json and messages.
const char* holeRepairName(HoleRepair r);

struct FilledHole {
    std::array<Label, 2> pair{};  ///< the regions the patch separates, lower label first
    std::size_t boundaryEdges = 0;
    double diameterMm = 0;        ///< largest distance between two of its boundary vertices
    Vec3 centre = Vec3::Zero();   ///< mean of its boundary vertices, mm
    HoleRepair how = HoleRepair::EarClipping;
    std::size_t triangles = 0;    ///< triangles of the patch, or of the lid taken out
};

struct HoleFillStats {
    std::vector<FilledHole> filled;  ///< every patch added, in the order made
    std::vector<FilledHole> left;    ///< loops no patch passed the checks for (how and triangles unset)
    std::size_t strayEdges = 0;      ///< open edges on no loop (HoleLoops::strayEdges)
    /// Edges of the repair flipped and triangles bumped to open a sharp region wedge
    /// (filters/PatchWedgeOpening.h, by the tet stage's repair), and the smallest wedge at the
    /// repair's edges before and after.
    std::size_t wedgeFlips = 0, wedgeBumps = 0;
    double smallestPatchWedgeBeforeDeg = 360, smallestPatchWedgeAfterDeg = 360;
    std::size_t trianglesAdded() const;
    std::size_t trianglesRemoved() const;  ///< lids'
    std::size_t verticesAdded() const;     ///< fan apexes
    double largestHoleMm() const;
};

/// As run.json's tetgen.hole_repair records it: the totals and every patch (label pair, boundary
/// edges, diameter and centre in mm, triangles, how it was closed).
nlohmann::json toJson(const HoleFillStats& stats);

/// Closes every hole it can, in place. Per loop: when the loop is the rim of a lid (a piece of the
/// sheet bounded only by open edges, within the loop: filters/HoleFlap.h) the lid is taken out;
/// else ear clipping in the loop's plane (never along an edge the surface already has), else its
/// triangulation of least area, else a fan from the loop's centroid; a patch is kept only when
/// no triangle of it is degenerate or intersects (exactly: filters/SelfIntersections.h) another
/// of its own or a surface triangle near the hole. When the patch so chosen makes a region wedge
/// under kHoleMinWedgeDeg with itself or the sheet (filters/PatchWedge.h), the clean one with the
/// widest smallest wedge among those and fans whose apex is raised or sunk along the loop's normal
/// by 1/8 to 1 loop radius, when no vertex of the surface and no seed lies between it and the first
/// (winding number): it then cannot have swept over a piece of the surface. The patch's triangles
/// carry the loop's label pair, wound as the loop (so each region's boundary closes with one
/// orientation) and with the sides in the order the sheet's triangles around the hole use. New
/// vertices are appended, vertices no triangle uses any more are dropped (indices change then);
/// the seeds are untouched. One pass: call again (holeLoops) to see what is left.
/// Cost: O(T log T) to find the loops plus O(T) per loop for the triangles near it.
HoleFillStats fillSurfaceHoles(InterfaceComplex& complex);

/// The smallest region wedge a hole patch should make: the simplifier's rule
/// (SimplifyOptions::minWedgeDeg), so a repaired complex holds no wedge the surface stage refuses.
constexpr double kHoleMinWedgeDeg = 20.0;

}  // namespace jawmesh
