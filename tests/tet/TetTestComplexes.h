// Small interface complexes built in code for the tet/ tests: a voxel "jaw block" (bone, two
// teeth with crowns above the crest, one-voxel PDL around each root) and nested spheres.
#pragma once

#include "io/InterfaceComplex.h"

#include <map>

namespace jawmesh::test {

/// A label per voxel; the complex is the set of faces between voxels of different labels.
struct VoxelScene {
    int nx = 0, ny = 0, nz = 0;
    double h = 1.0;  ///< voxel edge, mm
    std::vector<Label> labels;  ///< x fastest
    Label at(int i, int j, int k) const;
};

/// Bone block 16 x 8 x 8 voxels; teeth 24 and 25 with a 2 x 2 voxel root from z = 3 to the crest
/// (z = 8) and a crown up to z = 11; PDL = bone voxels within one voxel of a root.
VoxelScene jawBlockScene(double h = 1.0);

/// Interface complex of a voxel scene (quads split in two triangles, sides per the complex's
/// convention), one seed per voxel-connected component of each label.
InterfaceComplex complexFromVoxels(const VoxelScene& scene);

/// Exact region volumes of a voxel scene (count * h^3), mm^3.
std::map<Label, double> voxelVolumes(const VoxelScene& scene);

/// Region volumes enclosed by the complex's triangles (divergence theorem with the sides), mm^3.
std::map<Label, double> complexVolumes(const InterfaceComplex& complex);

/// Two teeth (icospheres r 1.0 around x = -/+1.7) in PDL shells (r 1.3) in a bone box
/// [-4, 4] x [-2.5, 2.5]^2 whose faces are tessellated at about `boxSpacing` mm.
InterfaceComplex nestedSpheresComplex(int subdivisions = 2, double boxSpacing = 0.5);

/// Tooth 24 (icosphere r 1.0) in a PDL shell `thicknessMm` thick whose outer sphere is turned
/// against the inner one, in a bone box [-2, 2]^3: a PDL one tet thick, whose tets TetGen under
/// -Y can only span between the two spheres' nodes (slivers where they do not face each other).
InterfaceComplex thinPdlComplex(double thicknessMm, int subdivisions);

}  // namespace jawmesh::test
