// Orientation repair of a dirty surface before inside tests: coincident vertices merged,
// degenerate and duplicate triangles dropped, triangle orientation made consistent across
// manifold edges, each patch turned to the area-weighted majority of its input triangles, and
// every patch that no other patch encloses turned outward. So a tooth with half its triangles
// flipped comes out outward, while a cavity shell given inward stays a cavity, and separate
// overlapping shells (dentin, enamel, pulp) each stay outward so that their union is inside.
#pragma once

#include "io/Progress.h"
#include "io/SurfaceMesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace jawmesh {

struct OrientedSurface {
    std::vector<Vec3> vertices;       ///< exactly coincident input vertices merged, mm
    std::vector<Tri> triangles;       ///< kept triangles, consistently oriented per patch
    std::vector<std::int32_t> patch;  ///< per triangle: id of its edge-manifold connected patch
    int patchCount = 0;
    std::size_t droppedDegenerate = 0;  ///< zero-area triangles (repeated or collinear corners)
    std::size_t droppedDuplicate = 0;   ///< triangles on the same three vertices as an earlier one
    std::size_t flipped = 0;            ///< kept triangles whose orientation was reversed
    int nestedPatches = 0;              ///< patches found inside another (orientation by majority)
};

/// Cleans and orients mesh (see the file comment). Patches are connected through edges shared by
/// exactly two triangles; a patch is "nested" when the other patches wind around a point of it.
/// Deterministic (independent of the thread count). Throws Cancelled when progress is cancelled.
/// Cost: O(n log n) sorting of vertices and edges, plus a few Embree lines per patch.
OrientedSurface orientSurface(const SurfaceMesh& mesh, Progress& progress = noProgress());

}  // namespace jawmesh
