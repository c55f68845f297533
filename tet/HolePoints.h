// Points through the holes for the quick tetrahedralization that cuts their patches (tet/HoleCut.h).
// Without them the tets at a hole are those of the surface around it, and the floods from its two
// sides meet on faces that reach a vertex of the sheet beside the hole: the patch then touches the
// sheet at that vertex and folds against it at a region wedge of a degree or two, which caps the
// dihedral angle of every tet at that edge (issue #27's bone-holes surface: wedges of 1.2-8.2 deg at
// three of its seven cut holes, 56 tets under 10 deg). With a lattice of points through each hole
// the floods meet on faces between those points, and the patch spans the hole on its own.
#pragma once

#include "filters/FillSurfaceHoles.h"
#include "io/SurfaceMesh.h"

#include <vector>

namespace jawmesh {

/// Per hole, the points of a cubic lattice (centred on the hole, spacing kHolePointSpacing times the
/// loop's mean edge, estimated as pi * diameter / edges, but at least the diameter over
/// kMaxHoleLatticeSpans) within the ball of radius half the diameter plus two spacings, leaving
/// out those nearer than half a spacing to a triangle of `surface` (a point next to the surface
/// would only make flat tets). In lattice order, hole by hole, until a hole's lattice would pass
/// kMaxHolePoints in all (that hole and the rest get none: their patches are cut as before).
/// Deterministic. Cost: O(T) per hole plus at most 37^3 lattice points, each against the
/// triangles in its cell.
std::vector<Vec3> pointsInHoles(const SurfaceMesh& surface, const std::vector<FilledHole>& holes);

/// Lattice spacing over the loop's mean edge: 2 left no new region wedge under 20 deg on the
/// bone-holes surface (1: the same, the quick tetrahedralization four times as long).
constexpr double kHolePointSpacing = 2.0;
/// A hole is never more lattice spacings across than this (a loop of many short edges would
/// otherwise fill its ball with millions of points).
constexpr double kMaxHoleLatticeSpans = 32.0;
/// Points for all holes together, so that many holes cannot swamp the quick run (the bone-holes
/// surface's seven cut holes take a few thousand).
constexpr std::size_t kMaxHolePoints = 200000;

}  // namespace jawmesh
