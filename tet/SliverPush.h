// The sliver improver's last resort (tet/ImproveSlivers.h, SliverOptions::interfacePushMm): an
// interface node of a tet still under the target, at an intrinsically thin spot of a region (a lip
// a few thousandths of a millimetre thick), is pushed away from the face opposite it by a bounded
// distance. The only operation that moves the surface; it records what each region's volume gains.
#pragma once

#include "io/SurfaceMesh.h"
#include "tet/ImproveSlivers.h"
#include "tet/SliverScore.h"
#include "tet/TetMeshEditor.h"

#include <cstdint>
#include <map>
#include <set>
#include <vector>

namespace jawmesh {

/// What the pushes made so far did: the nodes pushed (each is pushed once at most) and the volume
/// each label gained (negative: lost), mm^3, for the final volume check.
struct InterfacePushes {
    std::set<std::int32_t> pushed;
    std::map<Label, double> volumeChange;
};

/// The faces of the mesh's outer boundary (a tet face with no tet across: the surface against the
/// outside), as node triples, for the checks of pushes on it.
std::vector<Tri> outerBoundaryFaces(const TetMeshEditor& mesh);

/// For tet t (when alive and under the target): its interface nodes inside the mesh (not on its
/// outer boundary) and not pushed yet, lowest over their opposite face first, are tried pushed
/// straight away from that face by maxMm * i / 8 (i = 1..8); a node moves to the step with the
/// best objective over its star when the rule accepts it (each step over the best so far). The
/// first node that moves ends it (stats.interfacePushes, stats.largestPushMm).
/// With `outerFaces` (outerBoundaryFaces of the mesh), the nodes on the outer boundary instead:
/// their star holds every tet around them, but not the outside, so a step is taken only when the
/// boundary faces around the node then meet no other face of `outerFaces` (exact test), and the
/// push counts in stats.outerPushes too.
bool pushInterfaceNode(TetMeshEditor& mesh, std::int32_t t, double maxMm, Acceptance& accept, InterfacePushes& pushes,
                       SliverStats& stats, const std::vector<Tri>* outerFaces = nullptr);

}  // namespace jawmesh
