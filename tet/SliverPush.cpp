// The bounded push of an interface node off a thin spot (tet/SliverPush.h).
#include "tet/SliverPush.h"

#include "tet/SliverSmooth.h"

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

namespace jawmesh {

bool pushInterfaceNode(TetMeshEditor& mesh, std::int32_t t, double maxMm, Acceptance& accept, InterfacePushes& pushes,
                       SliverStats& stats) {
    if (!mesh.alive(t) || mesh.score(t) >= accept.target()) return false;
    const Tet e = mesh.tet(t);
    const auto P = [&](std::int32_t v) -> const Vec3& { return mesh.node(v); };
    std::array<std::pair<double, int>, 4> order;
    std::array<Vec3, 4> away;
    for (int k = 0; k < 4; ++k) {
        const Vec3 &a = P(e[std::size_t((k + 1) % 4)]), &b = P(e[std::size_t((k + 2) % 4)]), &c = P(e[std::size_t((k + 3) % 4)]);
        Vec3 n = (b - a).cross(c - a).normalized();
        if (n.dot(P(e[std::size_t(k)]) - a) < 0) n = -n;
        away[std::size_t(k)] = n;
        order[std::size_t(k)] = {n.dot(P(e[std::size_t(k)]) - a), k};
    }
    std::sort(order.begin(), order.end());
    for (const auto& [height, k] : order) {
        const std::int32_t v = e[std::size_t(k)];
        if (!mesh.fixed(v) || pushes.pushed.count(v) || mesh.onMeshBoundary(v)) continue;
        std::vector<Tet> tets;
        for (auto s : mesh.star(v)) tets.push_back(mesh.tet(s));
        Objective best = objectiveWith(mesh.nodes(), tets, v, P(v), accept.target());
        double bestStep = 0;
        for (int i = 1; i <= 8; ++i) {
            const double step = maxMm * i / 8.0;
            const Objective o = objectiveWith(mesh.nodes(), tets, v, P(v) + step * away[std::size_t(k)], accept.target());
            if (accept(o, best)) {
                best = o;
                bestStep = step;
            }
        }
        if (bestStep == 0) continue;
        for (auto s : mesh.star(v)) pushes.volumeChange[mesh.label(s)] -= mesh.volume(s);
        mesh.move(v, P(v) + bestStep * away[std::size_t(k)]);
        for (auto s : mesh.star(v)) pushes.volumeChange[mesh.label(s)] += mesh.volume(s);
        pushes.pushed.insert(v);
        ++stats.interfacePushes;
        stats.largestPushMm = std::max(stats.largestPushMm, bestStep);
        return true;
    }
    return false;
}

}  // namespace jawmesh
