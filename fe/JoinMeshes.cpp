// Implements fe/JoinMeshes.h; what it computes, its rules and its contract are documented there.
#include "fe/JoinMeshes.h"

#include "io/Error.h"

#include <set>

namespace jawmesh {

TetMesh joinMeshes(const TetMesh& first, const TetMesh& second) {
    const std::set<Label> firstLabels(first.labels.begin(), first.labels.end());
    for (Label l : second.labels)
        if (firstLabels.count(l)) throw Error("cannot join two meshes that both hold region " + labelName(l));
    TetMesh joined = first;
    const auto offset = static_cast<std::int32_t>(first.nodes.size());
    joined.nodes.insert(joined.nodes.end(), second.nodes.begin(), second.nodes.end());
    for (Tet t : second.tets) {
        for (std::int32_t& v : t) v += offset;
        joined.tets.push_back(t);
    }
    joined.labels.insert(joined.labels.end(), second.labels.begin(), second.labels.end());
    return joined;
}

}  // namespace jawmesh
