// Synthetic label fields for the filters tests: analytic regions (signed distance functions) sampled
// on a voxel grid, with per-region distance grids consistent with the labels, and checks shared by
// the tests (closed region boundaries, winding numbers, analytic distance to interfaces).
#pragma once

#include "io/InterfaceComplex.h"
#include "levelset/LabelField.h"

#include <functional>
#include <map>
#include <set>
#include <vector>

namespace jawmesh::test {

/// An analytic region: signed distance (mm, negative inside). Earlier regions win where they overlap.
struct AnalyticRegion {
    Label label;
    std::function<double(const Vec3&)> sdf;
};

struct SyntheticField {
    LabelField field;
    std::vector<AnalyticRegion> regions;
    /// Analytic signed distance of a region (outside: minus the minimum over all regions).
    double sdf(Label label, const Vec3& p) const;
    /// Analytic label at a point.
    Label labelAt(const Vec3& p) const;
};

/// Samples `regions` on voxels of size `voxel` covering box [lo, hi] (mm) plus a margin; distance
/// grids narrow-band (3 voxels) with inactive inside/outside values.
SyntheticField sampleField(const std::vector<AnalyticRegion>& regions, const Vec3& lo, const Vec3& hi,
                           double voxel);

/// Bone box 3 x 2 x 1.6 mm whose top (z = 0) is open to the outside, two teeth (capsules, radius
/// 0.45 mm, sticking out 0.6 mm above the crest), each in a PDL shell 0.2 mm thick inside the bone.
SyntheticField jawPhantom(double voxel = 0.05);

/// Label field given voxel by voxel (dims nx*ny*nz, x fastest), no distance fields.
LabelField rawField(const std::vector<Label>& labels, int nx, int ny, int nz, double voxel);

/// The region labels of a complex (every label on a side of a triangle but the outside).
std::set<Label> regionLabels(const InterfaceComplex& complex);

/// Label of the voxel nearest to p in a label field.
Label voxelLabelAt(const LabelField& field, const Vec3& p);

/// For region `label`: its boundary's edges each used by exactly one opposite pair of oriented
/// triangles (closed, consistently oriented, edge-manifold) and a single fan around every vertex
/// (vertex-manifold). Returns a message describing the first failure, empty when fine.
std::string checkRegionBoundary(const InterfaceComplex& complex, Label label);

/// Euler characteristic (V - E + F over the vertices and edges the triangles use) and number of
/// connected components of a surface. Cost: O(T log T) (millions of triangles in seconds).
std::pair<long, int> eulerAndComponents(const SurfaceMesh& m);

/// Generalized winding number of the closed surface at p.
double windingNumber(const SurfaceMesh& mesh, const Vec3& p);

}  // namespace jawmesh::test
