// Nodal forces equivalent to a uniform traction over a patch of faces, for decks that take nodal
// loads (CalculiX *CLOAD): the integral of the shape functions times the traction, face by face.
#pragma once

#include "fe/QuadraticTets.h"
#include "fe/Scenario.h"

#include <map>

namespace jawmesh {

/// Consistent nodal forces (N) of `load` (uniform traction load.traction() on its faces). Linear
/// faces (mids == nullptr): each corner gets area/3 of the face's force. Quadratic faces (mid-edge
/// nodes from `mids`): the corners get 0 and each mid-edge node area/3 — the exact integrals of the
/// 6-node triangle's shape functions. The forces sum to load.totalForceN.
/// Throws Error when a face edge has no mid-edge node in `mids`.
std::map<std::int32_t, Vec3> consistentNodalForces(const SurfaceLoad& load, const std::vector<Vec3>& nodes,
                                                   const EdgeMidNodes* mids = nullptr);

}  // namespace jawmesh
