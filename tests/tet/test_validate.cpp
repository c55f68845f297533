// validateTetMesh(): passes on good meshes, catches each deliberate defect, and is fast.
#include "io/Error.h"
#include "tet/GridTetMesh.h"
#include "tet/TetTestComplexes.h"
#include "tet/Tetrahedralize.h"
#include "tet/ValidateTetMesh.h"

#include <gtest/gtest.h>

#include <chrono>
#include <iostream>

using namespace jawmesh;
using namespace jawmesh::test;

namespace {

/// TetGen mesh of the voxel jaw block (teeth 24 and 25), computed once.
const TetMesh& jawMesh() {
    static const TetMesh mesh = [] {
        TetOptions o;
        o.pdlEdgeMm = 0.8, o.toothEdgeMm = 1.2, o.boneEdgeMm = 2.0;
        return tetrahedralize(complexFromVoxels(jawBlockScene(1.0)), o);
    }();
    return mesh;
}

std::size_t firstTetWithLabel(const TetMesh& m, Label l) {
    for (std::size_t t = 0; t < m.tets.size(); ++t)
        if (m.labels[t] == l) return t;
    return m.tets.size();
}

bool sharesNodeWithLabel(const TetMesh& m, std::size_t t, Label l) {
    for (std::size_t u = 0; u < m.tets.size(); ++u) {
        if (m.labels[u] != l) continue;
        for (auto a : m.tets[t])
            for (auto b : m.tets[u])
                if (a == b) return true;
    }
    return false;
}

}  // namespace

TEST(ValidateTetMesh, AcceptsTetgenMesh) {
    const ValidationReport r = validateTetMesh(jawMesh(), {24, 25});
    EXPECT_TRUE(r.valid()) << toJson(r).dump(1);
    EXPECT_GT(r.interfaceFaces, 0u);
    EXPECT_GT(r.boundaryFaces, 0u);
    EXPECT_GT(r.interfaceFacesPerPair.count({toothLabel(24), pdlLabel(24)}), 0u);
    EXPECT_GT(r.interfaceFacesPerPair.count({kMandibleBoneLabel, pdlLabel(25)}), 0u);
    EXPECT_NO_THROW(requireValid(jawMesh(), {24, 25}));
}

TEST(ValidateTetMesh, CatchesFlippedAndFlatTets) {
    TetMesh m = jawMesh();
    std::swap(m.tets[7][0], m.tets[7][1]);
    ValidationReport r = validateTetMesh(m, {24, 25});
    EXPECT_EQ(r.invertedTets, 1u);
    EXPECT_FALSE(r.valid());

    TetMesh flat = jawMesh();
    const Tet& t = flat.tets[0];
    const Vec3 mid = (flat.nodes[static_cast<std::size_t>(t[0])] + flat.nodes[static_cast<std::size_t>(t[1])] +
                      flat.nodes[static_cast<std::size_t>(t[2])]) / 3.0;
    flat.nodes.push_back(mid);  // a fourth node in the plane of the first three
    flat.tets.push_back({t[0], t[1], t[2], static_cast<std::int32_t>(flat.nodes.size() - 1)});
    flat.labels.push_back(flat.labels[0]);
    r = validateTetMesh(flat, {24, 25});
    EXPECT_GE(r.degenerateTets, 1u);
    EXPECT_FALSE(r.valid());
}

TEST(ValidateTetMesh, CatchesDuplicatedNodeAsNonConformal) {
    TetMesh m = jawMesh();
    // Give one tooth tet its own copy of a node it shares with the PDL: the faces it shares no
    // longer match (a crack), even though the geometry is unchanged.
    const std::size_t t = firstTetWithLabel(m, toothLabel(24));
    ASSERT_LT(t, m.tets.size());
    m.nodes.push_back(m.nodes[static_cast<std::size_t>(m.tets[t][0])]);
    m.tets[t][0] = static_cast<std::int32_t>(m.nodes.size() - 1);
    const ValidationReport r = validateTetMesh(m, {24, 25});
    EXPECT_EQ(r.duplicateNodes, 1u);
    EXPECT_GT(r.coincidentFaces, 0u);
    EXPECT_FALSE(r.valid());
    EXPECT_THROW(requireValid(m, {24, 25}), Error);
}

TEST(ValidateTetMesh, CatchesNonManifoldFaces) {
    TetMesh m = jawMesh();
    m.tets.push_back(m.tets[3]);  // the same tet twice
    m.labels.push_back(m.labels[3]);
    const ValidationReport r = validateTetMesh(m, {24, 25});
    EXPECT_GT(r.nonManifoldFaces, 0u);
    EXPECT_FALSE(r.valid());
}

TEST(ValidateTetMesh, CatchesMissingToothAndPdl) {
    TetMesh m = jawMesh();
    for (auto& l : m.labels)
        if (l == pdlLabel(25)) l = kMandibleBoneLabel;
    ValidationReport r = validateTetMesh(m, {24, 25});
    EXPECT_EQ(r.missingPdls, std::vector<int>{25});
    EXPECT_TRUE(r.missingTeeth.empty());
    EXPECT_FALSE(r.valid());

    r = validateTetMesh(jawMesh(), {24, 25, 26});
    EXPECT_EQ(r.missingTeeth, std::vector<int>{26});
    EXPECT_EQ(r.missingPdls, std::vector<int>{26});
    try {
        requireValid(jawMesh(), {24, 25, 26});
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("26"), std::string::npos) << e.what();
    }
}

TEST(ValidateTetMesh, CatchesPdlTouchingAnotherTooth) {
    TetMesh m = jawMesh();
    // Relabel the tets of pdl_24 that touch tooth 24 as pdl_25: pdl_25 now touches tooth 24.
    std::size_t changed = 0;
    for (std::size_t t = 0; t < m.tets.size() && changed < 3; ++t) {
        if (m.labels[t] != pdlLabel(24) || !sharesNodeWithLabel(m, t, toothLabel(24))) continue;
        m.labels[t] = pdlLabel(25);
        ++changed;
    }
    ASSERT_GT(changed, 0u);
    const ValidationReport r = validateTetMesh(m, {24, 25});
    EXPECT_GT(r.pdlForeignContacts + r.teethSharingNodes, 0u);
    EXPECT_GT(r.teethSharingNodes, 0u);
    EXPECT_FALSE(r.valid());
}

TEST(ValidateTetMesh, CatchesBadIndicesAndLabels) {
    TetMesh m = jawMesh();
    m.tets[0][2] = static_cast<std::int32_t>(m.nodes.size());
    EXPECT_EQ(validateTetMesh(m, {}).badIndices, 1u);
    TetMesh l = jawMesh();
    l.labels[0] = 77;
    EXPECT_EQ(validateTetMesh(l, {}).unknownLabels, 1u);
    TetMesh s = jawMesh();
    s.labels.pop_back();
    EXPECT_EQ(validateTetMesh(s, {}).sizeMismatch, 1u);
}

TEST(ValidateTetMesh, FastOnLargeMesh) {
    // 60 x 60 x 48 cubes x 6 = 1.04 M tets, bone with two "teeth" columns.
    const TetMesh m = gridTetMesh(60, 60, 48, 0.25, [](const Vec3& p) {
        if (p.z() > 6) return kMandibleBoneLabel;
        return p.x() < 7.5 ? toothLabel(24) : toothLabel(25);
    });
    const auto start = std::chrono::steady_clock::now();
    const ValidationReport r = validateTetMesh(m, {});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[ validate] " << m.tets.size() << " tets in " << seconds << " s\n";
    EXPECT_EQ(r.violationCount(), r.teethSharingNodes);  // the two columns touch: that is the only finding
    EXPECT_GT(r.teethSharingNodes, 0u);
    EXPECT_LT(seconds, 10.0);
}
