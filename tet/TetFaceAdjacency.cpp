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
    tbb::parallel_sort(adj.faces.begin(), adj.faces.end(), [](const TetFaceRef& a, const TetFaceRef& b) {
        if (a.key != b.key) return a.key < b.key;
        if (a.tet != b.tet) return a.tet < b.tet;
        return a.local < b.local;
    });
    adj.groupStart.reserve(2 * n + 2);
    for (std::size_t i = 0; i < adj.faces.size(); ++i) {
        if (i == 0 || adj.faces[i].key != adj.faces[i - 1].key) adj.groupStart.push_back(static_cast<std::int64_t>(i));
    }
    adj.groupStart.push_back(static_cast<std::int64_t>(adj.faces.size()));
    return adj;
}

}  // namespace jawmesh
