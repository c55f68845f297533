// Cavities for the sliver improver (tet/ImproveSlivers.h): Bowyer-Watson style regions of one
// label around a point, grown until the point sees every outer face, and the star of the point
// over those faces. The cavity star operation uses them inside one region, interface insertion
// (tet/SliverInterfaceInsert.h) in every region around a point on an interface.
#pragma once

#include "tet/ImproveSlivers.h"
#include "tet/SliverScore.h"
#include "tet/TetMeshEditor.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace jawmesh {

/// Which outer faces of a cavity to leave out of its star (sorted node triples).
using FaceFilter = std::function<bool(const std::array<std::int32_t, 3>&)>;

/// q strictly inside the circumsphere of the tet a, b, c, d (false for a degenerate tet).
bool insideCircumsphere(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& q);

/// Adds to `cavity` (tets of one region) the tets of that region connected to it through faces
/// whose circumsphere holds q (at most 64 tets in all).
void growCircumsphereCavity(const TetMeshEditor& mesh, std::vector<std::int32_t>& cavity, const Vec3& q);

/// Adds to `cavity` the region's tets behind every outer face that q does not see from inside,
/// until q sees them all (true) or such a face is on the region's boundary or the cavity grows
/// past 64 tets (false). TetGen's output is not Delaunay after improvement, so the circumsphere
/// cavity alone is not always star-shaped.
bool growUntilStarShaped(const TetMeshEditor& mesh, std::vector<std::int32_t>& cavity, const Vec3& q, const FaceFilter& skip = {});

/// The outer faces of `cavity` (faces of one of its tets only) but those `skip` names, each as
/// its tet with the opposite node replaced by -1: orientation kept, so with a new node there
/// every tet is positive exactly when that node sees the face from inside.
std::vector<Tet> starOfCavity(const TetMeshEditor& mesh, const std::vector<std::int32_t>& cavity, const FaceFilter& skip = {});

/// Cavity star: a new node near t (t's centroid, then points above t's region-boundary faces and
/// edges), the tets of t's region around it that it makes a star-shaped cavity of replaced by its
/// star, the node placed by the pattern search. The first start whose star the rule accepts is
/// made (stats.cavityStars). This is what a flat tet lying on two boundary faces at a ridge
/// needs: a node above the ridge, which no split of a single edge or face can reach.
bool starCavityAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats);

}  // namespace jawmesh
