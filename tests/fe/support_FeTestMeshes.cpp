// Implements the test helpers of fe/FeTestMeshes.h (documented there).
#include "fe/FeTestMeshes.h"

#include "tet/GridTetMesh.h"

namespace jawmesh::test {

TetMesh withoutOutside(const TetMesh& mesh) {
    TetMesh out;
    std::vector<std::int32_t> index(mesh.nodes.size(), -1);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        if (mesh.labels[t] == kOutsideLabel) continue;
        Tet tet;
        for (std::size_t i = 0; i < 4; ++i) {
            auto& id = index[static_cast<std::size_t>(mesh.tets[t][i])];
            if (id < 0) {
                id = static_cast<std::int32_t>(out.nodes.size());
                out.nodes.push_back(mesh.nodes[static_cast<std::size_t>(mesh.tets[t][i])]);
            }
            tet[i] = id;
        }
        out.tets.push_back(tet);
        out.labels.push_back(mesh.labels[t]);
    }
    return out;
}

TetMesh gridJawBlock() {
    auto label = [](const Vec3& p) -> Label {
        for (const auto& [unn, x0] : {std::pair<int, double>{24, 2.0}, {25, 6.0}}) {
            const bool tooth = p.x() > x0 && p.x() < x0 + 2 && p.y() > 1.5 && p.y() < 3.5 && p.z() > 1.5 && p.z() < 7;
            if (tooth) return toothLabel(unn);
            const bool pdl = p.x() > x0 - 0.5 && p.x() < x0 + 2.5 && p.y() > 1 && p.y() < 4 && p.z() > 1 && p.z() < 4;
            if (pdl) return pdlLabel(unn);
        }
        return p.z() < 4 ? kMandibleBoneLabel : kOutsideLabel;
    };
    return withoutOutside(gridTetMesh(20, 10, 14, 0.5, label));
}

TetMesh twoCrownBite() {
    return withoutOutside(gridTetMesh(8, 4, 28, 0.5, [](const Vec3& p) -> Label {
        const bool column = p.x() > 1 && p.x() < 3 && p.y() > 0.5 && p.y() < 1.5;
        if (column && p.z() > 5 && p.z() < 6.1) return toothLabel(24);
        if (column && p.z() > 6.6 && p.z() < 8) return toothLabel(9);
        return p.z() < 5 ? kMandibleBoneLabel : p.z() > 8 ? kMaxillaBoneLabel : kOutsideLabel;
    }));
}

std::map<int, ToothAxes> gridJawBlockAxes() {
    std::map<int, ToothAxes> axes;
    for (const auto& [unn, x] : {std::pair<int, double>{24, 3.0}, {25, 7.0}}) {
        ToothAxes a;
        a.crownCentre = Vec3(x, 2.5, 5.5);
        a.labial = -Vec3::UnitY();
        a.occlusal = Vec3::UnitZ();
        a.mesialDistal = Vec3(x < 5 ? -1.0 : 1.0, 0, 0);
        axes[unn] = a;
    }
    return axes;
}

}  // namespace jawmesh::test
