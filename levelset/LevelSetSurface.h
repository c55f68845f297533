// The iso-surface of a narrow-band level set as a closed, outward triangle mesh (OpenVDB
// volumeToMesh, quads split along their shorter diagonal): the phantom's surfaces and the label
// volumes' surfaces are both made by it.
#pragma once

#include "io/SurfaceMesh.h"

#include <openvdb/openvdb.h>

namespace jawmesh {

/// The iso-surface `isovalue` (0: the zero set) of a level set as a closed triangle mesh, oriented
/// outward (positive volume). Vertices lie on the linearly interpolated crossings (OpenVDB
/// volumeToMesh, adaptivity 0). Throws Error if the grid holds no surface. Cost: linear in the
/// active voxels.
SurfaceMesh extractLevelSetSurface(const openvdb::FloatGrid& grid, double isovalue = 0.0);

}  // namespace jawmesh
