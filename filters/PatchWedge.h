// The sharpest region wedge a hole patch would make where it is laid (filters/RegionWedges.h): at
// its own edges and where it meets the sheet around the hole. A wedge under the mesh's minimum
// dihedral angle caps every tet at that edge, so a patch that folds sharply against the sheet
// leaves slivers no improver can mend (docs/DESIGN.md, "The hole repair makes region wedges").
#pragma once

#include "io/InterfaceComplex.h"

#include <array>
#include <cstdint>
#include <vector>

namespace jawmesh {

/// Smallest region wedge, degrees, over the edges of `patch` laid into `complex`: its triangles index
/// complex.surface.vertices and then `added` (new points), are wound as they will be added and carry
/// `sides`; `near` lists the complex's triangles that may share an edge with it (the others are
/// not looked at). 360 when no region spans a wedge there. Cost: O(patch + near).
double patchSmallestWedgeDeg(const InterfaceComplex& complex, const std::vector<std::int32_t>& near, const std::vector<Tri>& patch,
                             const std::vector<Vec3>& added, const std::array<Label, 2>& sides);

}  // namespace jawmesh
