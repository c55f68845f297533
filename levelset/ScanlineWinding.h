// Exact winding numbers along the axis-parallel grid lines through voxel centres, by watertight
// scan conversion: every triangle is rasterised onto the lines of each axis with edge functions
// evaluated the same way by both triangles of a shared edge and a top-left tie rule, so a line
// through an edge or a vertex is counted exactly once (no slipping through, no double hits).
// A line whose signed crossings do not sum to zero passes through a hole (or a non-manifold
// defect) and abstains. This is the fast bulk of the inside test of meshToLevelSet().
#pragma once

#include "io/Progress.h"
#include "io/SurfaceMesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace jawmesh {

class ScanlineWinding {
public:
    /// indexVertices: positions in index space (world mm / voxel size), so voxel centres are the
    /// integer points; triangles oriented (outward shells, inward cavities). Builds the sorted
    /// crossing lists of every line of the 3 axes through the mesh's bounding box.
    /// Deterministic. Throws Cancelled. Cost: O(sum over triangles of the lines each covers) time,
    /// about 8 bytes per crossing plus 4 bytes per line of the bounding box, per axis.
    ScanlineWinding(const std::vector<Vec3>& indexVertices, const std::vector<Tri>& triangles,
                    Progress& progress = noProgress());

    /// Winding numbers of `count` consecutive voxels along axis (0 x, 1 y, 2 z) starting at
    /// coordinate `start`, on the line at u = coordinate (axis+1)%3, v = coordinate (axis+2)%3.
    /// Writes out[0..count). Returns false (out untouched) when the line is unreliable.
    bool windings(int axis, int u, int v, int start, int count, int* out) const;

    /// Number of crossings stored over all axes (for statistics).
    std::size_t crossingCount() const;

private:
    struct Crossing {
        float pos;            // index-space coordinate along the axis
        std::int32_t winding;  // winding number just after this crossing
    };
    struct Axis {
        int uMin = 0, vMin = 0, nu = 0, nv = 0;
        std::vector<std::uint32_t> offsets;  // nu*nv+1, line (u,v) at (u-uMin)*nv + (v-vMin)
        std::vector<Crossing> crossings;
    };
    std::array<Axis, 3> axes_;
};

}  // namespace jawmesh
