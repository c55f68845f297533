// Implements fe/QuadraticTets.h; what it computes, its rules and its contract are documented there.
#include "fe/QuadraticTets.h"

namespace jawmesh {

MixedTetMesh quadraticTetMesh(const TetMesh& mesh, EdgeMidNodes* midsOut) {
    MixedTetMesh q;
    q.nodes = mesh.nodes;
    q.labels = mesh.labels;
    q.tets.reserve(mesh.tets.size());
    EdgeMidNodes local;
    EdgeMidNodes& mids = midsOut ? *midsOut : local;
    mids.clear();
    mids.reserve(mesh.tets.size() * 2);
    for (const Tet& t : mesh.tets) {
        Tet10 e{};
        for (int i = 0; i < 4; ++i) e[static_cast<std::size_t>(i)] = t[static_cast<std::size_t>(i)];
        for (std::size_t k = 0; k < kGmshTet10Edges.size(); ++k) {
            const std::int32_t a = t[static_cast<std::size_t>(kGmshTet10Edges[k][0])];
            const std::int32_t b = t[static_cast<std::size_t>(kGmshTet10Edges[k][1])];
            const auto [it, inserted] = mids.emplace(edgeKey(a, b), static_cast<std::int32_t>(q.nodes.size()));
            if (inserted)
                q.nodes.push_back(0.5 * (mesh.nodes[static_cast<std::size_t>(a)] + mesh.nodes[static_cast<std::size_t>(b)]));
            e[4 + k] = it->second;
        }
        q.tets.push_back(e);
    }
    return q;
}

}  // namespace jawmesh
