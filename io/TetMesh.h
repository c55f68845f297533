// A labeled linear tetrahedral mesh: output of tet/, input of validation, metrics, FE and writers.
#pragma once

#include "io/Labels.h"
#include "io/SurfaceMesh.h"

#include <array>
#include <vector>

namespace jawmesh {

using Tet = std::array<std::int32_t, 4>;

struct TetMesh {
    std::vector<Vec3> nodes;     ///< mm
    std::vector<Tet> tets;       ///< positively oriented: (b-a)·((c-a)×(d-a)) > 0
    std::vector<Label> labels;   ///< one per tet
};

}  // namespace jawmesh
