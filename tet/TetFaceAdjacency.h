// Face adjacency of a tetrahedral mesh: every tet face, grouped by its three nodes. The one routine
// behind validation (conformity, manifoldness) and region-surface extraction.
#pragma once

#include "io/TetMesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace jawmesh {

/// One face of one tet. `key` is the three node indices sorted ascending (the face's identity);
/// `local` is the index (0..3) of the tet node opposite the face.
struct TetFaceRef {
    std::array<std::int32_t, 3> key;
    std::int32_t tet;
    std::int32_t local;
};

/// Faces sorted by (key, tet, local); faces with equal keys are consecutive and form a group.
/// Group g is faces[groupStart[g] .. groupStart[g+1]). A conformal manifold mesh has groups of size
/// 1 (boundary faces) and 2 (shared faces) only.
struct TetFaceAdjacency {
    std::vector<TetFaceRef> faces;
    std::vector<std::int64_t> groupStart;  ///< size = number of groups + 1
    std::size_t groupCount() const { return groupStart.empty() ? 0 : groupStart.size() - 1; }
    std::size_t groupSize(std::size_t g) const { return static_cast<std::size_t>(groupStart[g + 1] - groupStart[g]); }
};

/// Local node indices of the face opposite local node i, ordered so that the face normal (right-
/// hand rule) points out of a positively oriented tet (see io/TetMesh.h).
constexpr std::array<std::array<int, 3>, 4> kTetOutwardFaces = {{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

/// The three node indices of face `local` of tet t, outward for a positively oriented tet.
inline std::array<std::int32_t, 3> outwardFace(const Tet& t, int local) {
    const auto& f = kTetOutwardFaces[static_cast<std::size_t>(local)];
    return {t[static_cast<std::size_t>(f[0])], t[static_cast<std::size_t>(f[1])], t[static_cast<std::size_t>(f[2])]};
}

/// True when the triangles a and b (the same three nodes) are wound the same way: exact, where a
/// normal's dot product with the opposite node misjudges a flat tet.
inline bool sameWinding(const std::array<std::int32_t, 3>& a, const std::array<std::int32_t, 3>& b) {
    for (int k = 0; k < 3; ++k)
        if (a[0] == b[std::size_t(k)]) return a[1] == b[std::size_t((k + 1) % 3)];
    return false;
}

/// True when face group g lies inside one region: shared by two tets of the same label (not an
/// interface, not on the outside).
inline bool insideOneRegion(const TetFaceAdjacency& adj, const TetMesh& mesh, std::size_t g) {
    if (adj.groupSize(g) != 2) return false;
    const auto first = static_cast<std::size_t>(adj.groupStart[g]);
    return mesh.labels[static_cast<std::size_t>(adj.faces[first].tet)] ==
           mesh.labels[static_cast<std::size_t>(adj.faces[first + 1].tet)];
}

/// Builds the face adjacency of `mesh`.
/// Throws Error when a node index is out of range (validateTetMesh reports those before it asks).
/// Cost: O(T + N) (T tets, N nodes): a counting sort by each face's smallest node, then each
/// node's few faces sorted; result independent of the thread count.
TetFaceAdjacency tetFaceAdjacency(const TetMesh& mesh);

}  // namespace jawmesh
