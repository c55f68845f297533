// The angle a region spans around an interface edge (its "wedge"). Every tetrahedron of that region
// at the edge has a dihedral angle no larger than the wedge there, and TetGen with -Y cannot split the
// edge, so a wedge under the mesh's minimum dihedral angle can never be meshed well. The
// simplification refuses to create such wedges; the stats and tests measure them.
#pragma once

#include "io/InterfaceComplex.h"

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace jawmesh {

/// One triangle around an edge a-b, as the wedge computation needs it.
struct EdgeFanTriangle {
    Vec3 apex;          ///< the triangle's third vertex
    Label front, back;  ///< sides[0] (into which its normal points) and sides[1]
    bool aThenB;        ///< the triangle's vertex order runs a -> b (else b -> a)
};

/// Triangle t (which has a and b as corners) as it lies in the fan of edge a-b: its apex position
/// `apex` (the third vertex's) and the sides it carries.
inline EdgeFanTriangle edgeFanTriangle(const Tri& t, std::int32_t a, std::int32_t b, const Vec3& apex, const std::array<Label, 2>& sides) {
    std::size_t ia = 0;
    while (t[ia] != a) ++ia;
    return {apex, sides[0], sides[1], t[(ia + 1) % 3] == b};
}

/// The third vertex of triangle t besides a and b.
inline std::int32_t apexOf(const Tri& t, std::int32_t a, std::int32_t b) {
    for (const std::int32_t v : t)
        if (v != a && v != b) return v;
    return t[0];
}

/// How to read a pair of consecutive triangles whose facing labels disagree.
enum class FanKind {
    Partial,  ///< the fan may be seen only in part (e.g. at a block border): the pair is skipped
    Whole,    ///< every triangle on the edge is there: the surface folds, and the wedge is 0
};

/// Smallest angle, degrees, spanned between two consecutive triangles around the edge a-b by a region
/// other than the outside; 360 when there is none. A fold (a whole fan whose labels disagree
/// somewhere around the edge) is 0: no region can be given to the tets there, and TetGen's mesh
/// of it fails in the tet stage ("a region boundary is open"; issue #27, the punched mandible).
double smallestRegionWedgeDeg(const Vec3& a, const Vec3& b, const EdgeFanTriangle* fan, std::size_t n,
                              FanKind kind = FanKind::Partial);

struct RegionWedgeStats {
    double smallestDeg = 360;  ///< over every edge and region but the outside
    std::size_t edgesBelow = 0;  ///< edges with a wedge under the threshold asked for
    /// Those edges: midpoint (mm) and smallest wedge (degrees), by position.
    std::vector<std::pair<Vec3, double>> below;
};

/// Wedges of every edge of the complex (each edge once).
RegionWedgeStats measureRegionWedges(const InterfaceComplex& complex, double thresholdDeg);

}  // namespace jawmesh
