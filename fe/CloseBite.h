// Bringing the two jaws of a biting scenario into contact. Scans are taken with the mouth a little
// open, and a static solve cannot start from jaws apart: the mandible, free along the bite, would
// be a rigid body with nothing holding it until its crowns touch. So the mandible is first
// translated along the bite until a crown touches (frictionless elastic contact does not depend on
// the path, so the loaded state is the one a slow closing would reach).
#pragma once

#include "fe/ExteriorFaces.h"
#include "io/TetMesh.h"

#include <vector>

namespace jawmesh {

/// How far the mandible can move along the unit direction `up` before one of its crowns touches a
/// maxillary crown: the least distance along `up` from a node of a mandibular crown face to a
/// maxillary crown face, and along -up from a maxillary crown node to a mandibular crown face
/// (crown faces = exterior faces of tooth regions; vertex-face pairs only, so an edge-edge first
/// touch is missed by at most the curvature between nodes). 0 when a crown node already lies
/// inside the other jaw's crown; +inf when no crown faces the other jaw along `up`.
/// Cost: O(crown nodes x faces per cell), faces binned on a 1 mm grid across `up`.
double biteGapMm(const TetMesh& mesh, const std::vector<ExteriorFace>& exterior, const Vec3& up);

/// `mesh` with every node of the mandible's regions (bone 1, teeth 17-32 and their PDLs) moved by
/// `offsetMm`. Throws Error when a node belongs to both jaws (the jaws must be meshed apart).
TetMesh withMandibleMoved(const TetMesh& mesh, const Vec3& offsetMm);

}  // namespace jawmesh
