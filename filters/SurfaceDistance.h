// Directed distances from one surface to another (mm), the basis of the Hausdorff and mean
// distances and of the PDL thickness in the evaluation report.
//
// Definitions (docs/DESIGN.md, "Evaluation"):
//  - Area samples: each triangle of the `from` surface is cut into n^2 similar sub-triangles, n the
//    smallest giving sub-triangles no larger than an equilateral triangle of side `spacing` (and
//    n >= longest edge / (3 spacing) for slivers), at least 1; a sample is a sub-triangle's
//    centroid, weighted by its area. Means and percentiles are area-weighted over these samples.
//  - The maximum (directed Hausdorff distance) is over every point of the triangles, not just the
//    samples: a branch and bound subdivides only the triangles that could still beat the largest
//    sampled distance, using two upper bounds of the distance over a sub-triangle (Lipschitz: the
//    distance at a point plus the distance to the farthest corner; convexity: the distance to one
//    fixed triangle of `to` is convex, so its maximum over the sub-triangle is at a corner). The
//    result is exact up to `toleranceMm`.
// Every distance is the exact point-triangle distance to the nearest triangle (filters/TriangleBvh).
#pragma once

#include "filters/TriangleBvh.h"
#include "filters/WeightedDistribution.h"
#include "io/Progress.h"
#include "io/SurfaceMesh.h"

#include <cstdint>
#include <vector>

namespace jawmesh {

/// Area samples of `from` with their distance to `to`, in triangle order, n^2 per triangle.
struct DistanceSamples {
    std::vector<double> distanceMm;
    std::vector<double> weightMm2;              ///< sub-triangle area
    std::vector<std::int32_t> sourceTriangle;   ///< triangle of `from` the sample lies on
    std::vector<std::int32_t> closestTriangle;  ///< nearest triangle of `to` (lowest index on ties)
    std::vector<std::int64_t> firstOfTriangle;  ///< samples of triangle t: [first[t], first[t+1])
};

/// Samples `from` at `spacingMm` (> 0) and measures each sample's distance to `to` (non-empty).
/// Deterministic for any thread count. Throws Cancelled. Cost: one BVH query per sample, TBB-parallel.
DistanceSamples sampleDistances(const SurfaceMesh& from, const TriangleBvh& to, double spacingMm,
                                Progress& progress = noProgress());

/// Summary of the distances of one group of `from` triangles.
struct DistanceSummary {
    Distribution distance;  ///< area-weighted over the samples; max refined (see the file comment)
    Vec3 maxAt = Vec3::Zero();  ///< a point where the max is attained
    double areaMm2 = 0;
};

/// Per group, the distances from `from` to `to` summarised: groupOfTriangle[t] in [0, groupCount)
/// or -1 (triangle ignored). `samples` must come from sampleDistances(from, to, ...). The max of
/// each group is refined to within toleranceMm (> 0). Deterministic for any thread count.
/// Throws Cancelled. Cost: O(samples), one query per vertex of a grouped triangle (the corners the
/// refinement starts from, which also raise each group's starting bar), plus the refinement.
std::vector<DistanceSummary> summarizeDistances(const SurfaceMesh& from, const DistanceSamples& samples,
                                                const std::vector<int>& groupOfTriangle, int groupCount,
                                                const TriangleBvh& to, double toleranceMm,
                                                Progress& progress = noProgress());

}  // namespace jawmesh
