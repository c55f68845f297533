// Implements tet/UnusedNodes.h; what it computes, its rules and its contract are documented there.
#include "tet/UnusedNodes.h"

#include <cstdint>
#include <vector>

namespace jawmesh {

std::size_t dropUnusedNodes(TetMesh& mesh) {
    std::vector<std::int32_t> newIndex(mesh.nodes.size(), -1);
    for (const Tet& t : mesh.tets)
        for (std::int32_t v : t) newIndex[static_cast<std::size_t>(v)] = 0;
    std::int32_t next = 0;
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
        if (newIndex[i] < 0) continue;
        newIndex[i] = next;
        mesh.nodes[static_cast<std::size_t>(next++)] = mesh.nodes[i];
    }
    const std::size_t dropped = mesh.nodes.size() - static_cast<std::size_t>(next);
    mesh.nodes.resize(static_cast<std::size_t>(next));
    for (Tet& t : mesh.tets)
        for (std::int32_t& v : t) v = newIndex[static_cast<std::size_t>(v)];
    return dropped;
}

}  // namespace jawmesh
