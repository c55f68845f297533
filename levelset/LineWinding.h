// Winding number of a point from one full straight line through it, with Embree. The line runs
// from far outside the mesh to far outside on the other side; every triangle it crosses is
// collected (Embree's filter rejects each hit so traversal goes on), hits at the same place
// with the same direction (a shared edge hit twice, a duplicate face) count once, and the signed
// crossings must add up to zero, otherwise the line slipped through a hole or an edge and
// abstains. One line is a vote, never a verdict: callers vote over several lines.
#pragma once

#include "io/SurfaceMesh.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace jawmesh {

class LineWindingQuery {
public:
    /// Builds an Embree BVH over the triangles (mm). patch[t] groups triangles (e.g. connected
    /// components) so a query can ignore one group; pass an empty vector for "one group".
    /// The vectors are copied. Throws Error if Embree fails. Cost: O(n log n), parallel.
    LineWindingQuery(const std::vector<Vec3>& vertices, const std::vector<Tri>& triangles,
                     const std::vector<std::int32_t>& patch);
    ~LineWindingQuery();
    LineWindingQuery(const LineWindingQuery&) = delete;
    LineWindingQuery& operator=(const LineWindingQuery&) = delete;

    /// Per-triangle orientation (+1 as given, -1 flipped) used by later queries; default all +1.
    void setOrientation(std::vector<std::int8_t> sign);

    /// Winding number at p (mm) counted along the full line through p with direction dir
    /// (need not be unit), ignoring triangles of patch ignorePatch (-1: none). Entering through
    /// the front of an outward triangle counts +1. Returns nullopt when the crossings along the
    /// whole line do not sum to zero (unreliable line). Thread-safe. Cost: one Embree traversal
    /// collecting every hit on the line, O(hits log hits) after it.
    std::optional<int> windingAlongLine(const Vec3& p, const Vec3& dir, std::int32_t ignorePatch = -1) const;

    /// A fixed sequence of well-spread unit directions avoiding the axes and diagonals (a golden
    /// spiral of 64 points, k taken modulo 64), for callers that vote over several lines.
    static Vec3 genericDirection(int k);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace jawmesh
