// Small labeled tet meshes with known geometry for the fe/ tests, built without the pipeline.
#pragma once

#include "io/TetMesh.h"
#include "io/ToothAxes.h"

#include <map>

namespace jawmesh::test {

/// A structured "jaw block" (0.5 mm cubes, 6 tets each): mandible bone x in [0, 10], y in [0, 5],
/// z in [0, 4] (crest at z = 4); teeth 24 (x in [2, 4]) and 25 (x in [6, 8]), y in [1.5, 3.5],
/// z in [1.5, 7] (crown above the crest); a 0.5 mm PDL around each root inside the bone. Outside
/// cells are dropped and nodes compacted.
TetMesh gridJawBlock();

/// Axes of the block's teeth by construction: crown centre (x, 2.5, 5.5), labial -y, occlusal +z,
/// distal away from x = 5.
std::map<int, ToothAxes> gridJawBlockAxes();

/// The smallest biting case (0.5 mm cubes): mandible bone z in [0, 5] with tooth 24's crown
/// x in [1, 3], y in [0.5, 1.5], z in [5, 6]; 0.5 mm above it tooth 9's crown (z in [6.5, 8]) under
/// the maxilla bone z in [8, 14]. One mesh, the crowns sharing no node.
TetMesh twoCrownBite();

/// Drops tets labeled 0 and nodes no tet uses (indices compacted in order).
TetMesh withoutOutside(const TetMesh& mesh);

}  // namespace jawmesh::test
