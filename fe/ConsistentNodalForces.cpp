// Implements fe/ConsistentNodalForces.h; what it computes, its rules and its contract are documented there.
#include "fe/ConsistentNodalForces.h"

#include "fe/ExteriorFaces.h"
#include "io/Error.h"

namespace jawmesh {

std::map<std::int32_t, Vec3> consistentNodalForces(const SurfaceLoad& load, const std::vector<Vec3>& nodes,
                                                   const EdgeMidNodes* mids) {
    std::map<std::int32_t, Vec3> forces;
    const Vec3 traction = load.traction();
    for (const Tri& t : load.faces) {
        const Vec3 share = traction * (triangleArea(nodes, t) / 3.0);
        for (int i = 0; i < 3; ++i) {
            std::int32_t node = t[static_cast<std::size_t>(i)];
            if (mids) {
                const auto it = mids->find(edgeKey(node, t[static_cast<std::size_t>((i + 1) % 3)]));
                if (it == mids->end()) throw Error("load '" + load.name + "': a face edge has no mid-edge node");
                node = it->second;
            }
            auto [entry, inserted] = forces.emplace(node, Vec3::Zero());
            entry->second += share;
        }
    }
    return forces;
}

}  // namespace jawmesh
