// Edge and face splits for the sliver improver (tet/SliverSplits.h).
#include "tet/SliverSplits.h"

#include "tet/SliverSmooth.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace jawmesh {

bool splitEdgeAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats) {
    const Tet e = mesh.tet(t);
    std::vector<std::pair<double, std::pair<std::int32_t, std::int32_t>>> edges;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            const std::int32_t a = e[std::size_t(i)], b = e[std::size_t(j)];
            edges.push_back({-(mesh.node(a) - mesh.node(b)).squaredNorm(), {std::min(a, b), std::max(a, b)}});
        }
    std::sort(edges.begin(), edges.end());
    for (const auto& [negLen, ab] : edges) {
        const auto [a, b] = ab;
        const std::vector<std::int32_t> ring = mesh.interiorRing(a, b, mesh.label(t));
        if (ring.empty()) continue;
        const auto m = std::int32_t(mesh.nodeCount());  // the new node (not yet added)
        std::vector<Tet> fresh;
        for (auto s : ring) {
            Tet x = mesh.tet(s), y = x;
            for (auto& v : x)
                if (v == a) v = m;
            for (auto& v : y)
                if (v == b) v = m;
            fresh.push_back(x);
            fresh.push_back(y);
        }
        mesh.addNode(0.5 * (mesh.node(a) + mesh.node(b)), false);
        const auto [p, after] = bestOfStarts(mesh, fresh, m, ring, accept.target());
        mesh.placeNewNode(p);
        if (!accept(after, objectiveOf(mesh, ring, accept.target())) || !mesh.fillsSameVolume(ring, fresh)) {
            mesh.dropNewNode();
            continue;
        }
        mesh.replace(ring, fresh, mesh.label(t));
        ++stats.splits;
        return true;
    }
    return false;
}

bool splitFaceAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats) {
    const Label label = mesh.label(t);
    for (int k = 0; k < 4; ++k) {
        std::int32_t f[3];
        const std::int32_t other = mesh.sameRegionNeighbour(t, k, f);
        if (other < 0) continue;
        const auto m = std::int32_t(mesh.nodeCount());
        std::vector<Tet> fresh;
        for (auto s : {t, other}) {
            const Tet g = mesh.tet(s);
            for (int i = 0; i < 4; ++i) {  // replace each face node by m in turn: orientation kept
                if (std::find(f, f + 3, g[std::size_t(i)]) == f + 3) continue;
                Tet x = g;
                x[std::size_t(i)] = m;
                fresh.push_back(x);
            }
        }
        mesh.addNode((mesh.node(f[0]) + mesh.node(f[1]) + mesh.node(f[2])) / 3.0, false);
        const auto [p, after] = bestOfStarts(mesh, fresh, m, {t, other}, accept.target());
        mesh.placeNewNode(p);
        if (!accept(after, objectiveOf(mesh, {t, other}, accept.target())) || !mesh.fillsSameVolume({t, other}, fresh)) {
            mesh.dropNewNode();
            continue;
        }
        mesh.replace({t, other}, fresh, label);
        ++stats.faceSplits;
        return true;
    }
    return false;
}

}  // namespace jawmesh
