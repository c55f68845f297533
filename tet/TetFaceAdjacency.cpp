// Implements tet/TetFaceAdjacency.h; what it computes, its rules and its contract are documented there.
#include "tet/TetFaceAdjacency.h"

#include "io/Error.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace jawmesh {
namespace {

/// Every face of every tet with its key sorted, in (tet, local) order.
std::vector<TetFaceRef> facesInTetOrder(const TetMesh& mesh) {
    const std::size_t n = mesh.tets.size();
    std::vector<TetFaceRef> faces(4 * n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t)
            for (int i = 0; i < 4; ++i) {
                auto key = outwardFace(mesh.tets[t], i);
                std::sort(key.begin(), key.end());
                faces[4 * t + static_cast<std::size_t>(i)] = {key, static_cast<std::int32_t>(t), i};
            }
    });
    return faces;
}

/// Stable sort of one node's faces by their two other nodes (a few dozen on average: no buffer).
void insertionSortByOtherNodes(TetFaceRef* begin, TetFaceRef* end) {
    const auto before = [](const TetFaceRef& a, const TetFaceRef& b) {
        return a.key[1] != b.key[1] ? a.key[1] < b.key[1] : a.key[2] < b.key[2];
    };
    for (TetFaceRef* i = begin + (begin != end); i < end; ++i) {
        const TetFaceRef f = *i;
        TetFaceRef* j = i;
        for (; j != begin && before(f, *(j - 1)); --j) *j = *(j - 1);
        *j = f;
    }
}

}  // namespace

TetFaceAdjacency tetFaceAdjacency(const TetMesh& mesh) {
    const std::vector<TetFaceRef> inTetOrder = facesInTetOrder(mesh);
    // Counting sort by the smallest node, then each node's few faces by the other two: the order
    // of a comparison sort by (key, tet, local), since the scatter keeps (tet, local) order within
    // a node. A parallel comparison sort of the 4T faces was most of this function's time.
    const std::size_t nodes = mesh.nodes.size();
    std::vector<std::int64_t> start(nodes + 1, 0);
    for (const TetFaceRef& f : inTetOrder) {
        if (f.key[0] < 0 || static_cast<std::size_t>(f.key[2]) >= nodes)
            throw Error("tet face adjacency: tet " + std::to_string(f.tet) + " has a node index out of range");
        ++start[static_cast<std::size_t>(f.key[0]) + 1];
    }
    for (std::size_t v = 0; v < nodes; ++v) start[v + 1] += start[v];
    TetFaceAdjacency adj;
    adj.faces.resize(inTetOrder.size());
    std::vector<std::int64_t> next(start.begin(), start.end() - 1);
    for (const TetFaceRef& f : inTetOrder) adj.faces[static_cast<std::size_t>(next[static_cast<std::size_t>(f.key[0])]++)] = f;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nodes, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t v = r.begin(); v != r.end(); ++v)
            insertionSortByOtherNodes(adj.faces.data() + start[v], adj.faces.data() + start[v + 1]);
    });
    adj.groupStart.reserve(inTetOrder.size() / 2 + 2);
    for (std::size_t i = 0; i < adj.faces.size(); ++i) {
        const auto& k = adj.faces[i].key;
        if (i == 0 || k[0] != adj.faces[i - 1].key[0] || k[1] != adj.faces[i - 1].key[1] || k[2] != adj.faces[i - 1].key[2])
            adj.groupStart.push_back(static_cast<std::int64_t>(i));
    }
    adj.groupStart.push_back(static_cast<std::int64_t>(adj.faces.size()));
    return adj;
}

}  // namespace jawmesh
