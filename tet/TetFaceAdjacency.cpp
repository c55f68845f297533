// Implements tet/TetFaceAdjacency.h; what it computes, its rules and its contract are documented there.
#include "tet/TetFaceAdjacency.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>

namespace jawmesh {

TetFaceAdjacency tetFaceAdjacency(const TetMesh& mesh) {
    TetFaceAdjacency adj;
    const std::size_t n = mesh.tets.size();
    adj.faces.resize(4 * n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            for (int i = 0; i < 4; ++i) {
                auto key = outwardFace(mesh.tets[t], i);
                std::sort(key.begin(), key.end());
                adj.faces[4 * t + static_cast<std::size_t>(i)] = {key, static_cast<std::int32_t>(t), i};
            }
        }
    });
    // A total order (ties broken by tet and local index) keeps the result thread-count independent.
    // Keys are compared component by component: std::array's operators call memcmp, which took
    // about a third of this function's time.
    tbb::parallel_sort(adj.faces.begin(), adj.faces.end(), [](const TetFaceRef& a, const TetFaceRef& b) {
        if (a.key[0] != b.key[0]) return a.key[0] < b.key[0];
        if (a.key[1] != b.key[1]) return a.key[1] < b.key[1];
        if (a.key[2] != b.key[2]) return a.key[2] < b.key[2];
        if (a.tet != b.tet) return a.tet < b.tet;
        return a.local < b.local;
    });
    adj.groupStart.reserve(2 * n + 2);
    for (std::size_t i = 0; i < adj.faces.size(); ++i) {
        const auto& k = adj.faces[i].key;
        if (i == 0 || k[0] != adj.faces[i - 1].key[0] || k[1] != adj.faces[i - 1].key[1] || k[2] != adj.faces[i - 1].key[2])
            adj.groupStart.push_back(static_cast<std::int64_t>(i));
    }
    adj.groupStart.push_back(static_cast<std::int64_t>(adj.faces.size()));
    return adj;
}

}  // namespace jawmesh
