// Two jaws' meshes as one (fe/JoinMeshes.h).
#include "fe/JoinMeshes.h"
#include "fe/FeTestMeshes.h"
#include "io/Error.h"

#include <gtest/gtest.h>

namespace jawmesh {
namespace {

TEST(JoinMeshes, KeepsBothMeshesApartWithTheSecondRenumbered) {
    const TetMesh lower = test::gridJawBlock();
    TetMesh upper = lower;
    for (Vec3& p : upper.nodes) p = Vec3(p.x(), p.y(), 20.0 - p.z());  // mirrored above
    for (Tet& t : upper.tets) std::swap(t[0], t[1]);                      // positive again
    for (Label& l : upper.labels)
        l = labelKind(l) == LabelKind::Bone ? boneLabel(Jaw::Maxilla)
            : labelKind(l) == LabelKind::Tooth ? toothLabel(labelUnn(l) - 16) : pdlLabel(labelUnn(l) - 16);
    const TetMesh both = joinMeshes(lower, upper);
    ASSERT_EQ(both.nodes.size(), lower.nodes.size() + upper.nodes.size());
    ASSERT_EQ(both.tets.size(), lower.tets.size() + upper.tets.size());
    for (std::size_t t = 0; t < upper.tets.size(); ++t) {
        const Tet& joined = both.tets[lower.tets.size() + t];
        EXPECT_EQ(both.labels[lower.tets.size() + t], upper.labels[t]);
        for (std::size_t i = 0; i < 4; ++i)
            EXPECT_EQ(both.nodes[static_cast<std::size_t>(joined[i])], upper.nodes[static_cast<std::size_t>(upper.tets[t][i])]);
    }
    EXPECT_THROW(joinMeshes(lower, lower), Error);  // the same jaw twice
}

}  // namespace
}  // namespace jawmesh
