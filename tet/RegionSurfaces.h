// Per-region boundary surfaces extracted from a labeled tet mesh (the surface_meshes/ outputs):
// for each label, the faces of its tets whose other side is another label or the outside.
#pragma once

#include "io/InterfaceComplex.h"
#include "io/SurfaceMesh.h"
#include "io/TetMesh.h"

#include <map>
#include <string>
#include <vector>

namespace jawmesh {

/// A region's boundary surface with, for each triangle, the label on its other side (kOutsideLabel
/// on the outside): lets metrics split a surface by neighbour (a tooth's crown faces the outside,
/// its root the PDL or bone).
struct RegionBoundary {
    SurfaceMesh surface;
    std::vector<Label> otherSide;  ///< one per surface triangle
};

/// As regionSurfaces(), keeping the label across each triangle (for a face shared by more than two
/// tets, the first other label in adjacency order). Cost: as regionSurfaces().
std::map<Label, RegionBoundary> regionBoundaries(const TetMesh& mesh);

/// Boundary surface of every region of `mesh`, keyed by label: closed wherever the region is,
/// oriented outward (normals point out of the region; tets must be positively oriented), vertices
/// compacted in increasing node order. An interface face appears in both regions' surfaces with
/// opposite orientations. Cost: one face adjacency (O(T log T)) plus O(faces).
std::map<Label, SurfaceMesh> regionSurfaces(const TetMesh& mesh);

/// The interface complex a labeled tet mesh carries: every face between two labels or on the
/// outside, with sides as in filters/ExtractInterfaces.h (sides[t][0] the smaller label, the normal
/// pointing into it), vertices compacted in increasing node order, no seeds. For a mesh TetGen made
/// with -Y these are the interface triangles it was given. Cost: one face adjacency.
InterfaceComplex meshInterfaces(const TetMesh& mesh);

/// File name of a region's surface in surface_meshes/: "bone.stl", "tooth_24.stl", "pdl_24.stl".
/// Throws Error for the outside label or unknown labels.
std::string regionSurfaceFileName(Label label);

/// Writes every region's surface into `folder` (binary STL, atomically, names as above; a mesh
/// with both bones writes bone_mandible.stl and bone_maxilla.stl).
/// Throws Error on I/O failure. Returns the paths written, in label order.
std::vector<std::string> writeRegionSurfaces(const TetMesh& mesh, const std::string& folder);

}  // namespace jawmesh
