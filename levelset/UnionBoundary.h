// The boundary of the union of a surface's shells (issue #27): a tooth exported as overlapping
// enamel, dentin and pulp shells holds faces inside the union (inner walls, the pulp) that bound
// nothing. The level sets drop them (levelset/MeshToLevelSet.h); the evaluation measures against
// what is left, so a multi-shell tooth is compared with its union, not with its pulp.
#pragma once

#include "io/Case.h"
#include "io/SurfaceMesh.h"
#include "levelset/LineWinding.h"

namespace jawmesh {

/// Whether triangle abc has the union's inside on both of its sides or on neither: winding
/// numbers (>= 1 inside) `offsetMm` off both faces along a few of LineWindingQuery's lines
/// (starting at `firstLine`), two agreeing votes decide; false when the lines disagree or abstain.
bool bothSidesAlike(const LineWindingQuery& query, const Vec3& a, const Vec3& b, const Vec3& c, double offsetMm, int firstLine);

/// The triangles of `mesh` on the boundary of the union of its shells, after orientation repair
/// (levelset/OrientSurface.h); a surface of one patch is returned as it is (nothing to drop).
/// Cost: one Embree BVH and 4-10 lines per triangle when it has several patches.
SurfaceMesh unionBoundary(const SurfaceMesh& mesh);

/// unionBoundary of every tooth (the bone, 1-2 M triangles, is left as it is: the multi-
/// shell inputs are teeth, and its lines would cost the evaluation seconds per run).
JawSurfaces toothUnionBoundaries(JawSurfaces surfaces);

}  // namespace jawmesh
