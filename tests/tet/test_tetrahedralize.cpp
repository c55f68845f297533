// tetrahedralize() on small complexes built in code: labels, conformity, quality, exact volumes,
// grading, and errors for bad input.
#include "filters/ExtractInterfaces.h"
#include "io/Error.h"
#include "support/TiledSlabField.h"
#include "tet/ElementQuality.h"
#include "tet/TetFaceAdjacency.h"
#include "tet/TetTestComplexes.h"
#include "tet/Tetrahedralize.h"
#include "tet/ValidateTetMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <set>

using namespace jawmesh;
using namespace jawmesh::test;

namespace {

TetOptions gradedOptions() {
    TetOptions o;
    o.radiusEdgeRatio = 1.5;
    o.slivers.targetMinDihedralDeg = 10.0;
    o.pdlEdgeMm = 0.6;
    o.toothEdgeMm = 1.0;
    o.boneEdgeMm = 2.0;
    return o;
}

std::map<Label, double> tetVolumes(const TetMesh& m) {
    std::map<Label, double> v;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        const Tet& e = m.tets[t];
        const Vec3& a = m.nodes[static_cast<std::size_t>(e[0])];
        v[m.labels[t]] += (m.nodes[static_cast<std::size_t>(e[1])] - a)
                              .dot((m.nodes[static_cast<std::size_t>(e[2])] - a).cross(m.nodes[static_cast<std::size_t>(e[3])] - a)) / 6.0;
    }
    return v;
}

/// Every input triangle is one face of the output: shared by two tets carrying its two sides, or
/// a boundary face of the tet on its labeled side when the other side is outside.
void expectInterfacesPreserved(const InterfaceComplex& plc, const TetMesh& mesh) {
    const TetFaceAdjacency adj = tetFaceAdjacency(mesh);
    std::map<std::array<std::int32_t, 3>, std::size_t> groupOf;
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        // Faces are keyed by output node positions; map them back through coordinates.
        groupOf[adj.faces[static_cast<std::size_t>(adj.groupStart[g])].key] = g;
    }
    std::map<std::array<double, 3>, std::int32_t> nodeAt;
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) nodeAt[{mesh.nodes[i].x(), mesh.nodes[i].y(), mesh.nodes[i].z()}] = static_cast<std::int32_t>(i);
    std::size_t missing = 0, wrong = 0;
    for (std::size_t t = 0; t < plc.surface.triangles.size(); ++t) {
        std::array<std::int32_t, 3> key;
        bool found = true;
        for (std::size_t k = 0; k < 3; ++k) {
            const Vec3& p = plc.surface.vertices[static_cast<std::size_t>(plc.surface.triangles[t][k])];
            const auto it = nodeAt.find({p.x(), p.y(), p.z()});
            if (it == nodeAt.end()) found = false;
            else key[k] = it->second;
        }
        std::sort(key.begin(), key.end());
        const auto it = found ? groupOf.find(key) : groupOf.end();
        if (it == groupOf.end()) {
            ++missing;
            continue;
        }
        const std::size_t g = it->second, begin = static_cast<std::size_t>(adj.groupStart[g]);
        std::array<Label, 2> got = {mesh.labels[static_cast<std::size_t>(adj.faces[begin].tet)],
                                    adj.groupSize(g) == 2 ? mesh.labels[static_cast<std::size_t>(adj.faces[begin + 1].tet)] : kOutsideLabel};
        std::array<Label, 2> want = plc.sides[t];
        std::sort(got.begin(), got.end());
        std::sort(want.begin(), want.end());
        if (got != want || adj.groupSize(g) > 2) ++wrong;
    }
    EXPECT_EQ(missing, 0u) << "input triangles not found as faces of the tet mesh";
    EXPECT_EQ(wrong, 0u) << "input triangles whose tets do not carry their two sides";
}

void expectGoodMesh(const InterfaceComplex& plc, const TetMesh& mesh, const std::map<Label, double>& expectedVolumes,
                    const TetStats& stats, const std::string& name) {
    const ValidationReport report = validateTetMesh(mesh, {24, 25});
    EXPECT_TRUE(report.valid()) << toJson(report).dump(1);
    EXPECT_EQ(report.unusedNodes, 0u);

    std::set<Label> present(mesh.labels.begin(), mesh.labels.end());
    EXPECT_EQ(present, (std::set<Label>{kMandibleBoneLabel, toothLabel(24), toothLabel(25), pdlLabel(24), pdlLabel(25)}));

    const QualityStats q = measureQuality(mesh, 10.0);
    EXPECT_GE(q.minDihedralDeg, 10.0);
    EXPECT_EQ(q.belowDihedralThreshold, 0u);

    const auto volumes = tetVolumes(mesh);
    for (const auto& [label, expected] : expectedVolumes) {
        ASSERT_TRUE(volumes.count(label)) << labelName(label);
        EXPECT_NEAR(volumes.at(label), expected, 1e-6 * expected) << labelName(label);
    }
    expectInterfacesPreserved(plc, mesh);

    std::cout << "[ tetgen  ] " << name << ": " << stats.inputTriangles << " input triangles -> " << stats.tets
              << " tets, " << stats.nodes << " nodes in " << stats.seconds << " s (" << stats.attempts
              << " run(s), switches " << stats.switches << "); min dihedral " << q.minDihedralDeg << " deg, max dihedral "
              << q.maxDihedralDeg << " deg, max radius-edge " << q.maxRadiusEdge << "\n";
}

double meanTetVolume(const TetMesh& m, LabelKind kind) {
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        if (labelKind(m.labels[t]) != kind) continue;
        const Tet& e = m.tets[t];
        const Vec3& a = m.nodes[static_cast<std::size_t>(e[0])];
        sum += (m.nodes[static_cast<std::size_t>(e[1])] - a)
                   .dot((m.nodes[static_cast<std::size_t>(e[2])] - a).cross(m.nodes[static_cast<std::size_t>(e[3])] - a)) / 6.0;
        ++n;
    }
    return n ? sum / static_cast<double>(n) : 0.0;
}

}  // namespace

TEST(Tetrahedralize, JawBlockIsLabeledConformalExactAndGraded) {
    const VoxelScene scene = jawBlockScene(1.0);
    const InterfaceComplex plc = complexFromVoxels(scene);
    TetStats stats;
    const TetMesh mesh = tetrahedralize(plc, gradedOptions(), noProgress(), &stats);
    expectGoodMesh(plc, mesh, voxelVolumes(scene), stats, "jaw block (voxels)");
    EXPECT_EQ(stats.belowMinDihedral, 0u);
    // Grading: teeth finer than bone. (The one-voxel PDL cannot be refined with -Y: every
    // interior point would encroach upon its preserved facets.)
    EXPECT_LT(meanTetVolume(mesh, LabelKind::Tooth), meanTetVolume(mesh, LabelKind::Bone));
}

TEST(Tetrahedralize, GradedWhenInterfacesMayBeSplit) {
    const VoxelScene scene = jawBlockScene(1.0);
    const InterfaceComplex plc = complexFromVoxels(scene);
    TetOptions o = gradedOptions();
    o.pdlEdgeMm = 0.8, o.toothEdgeMm = 1.2, o.boneEdgeMm = 2.5;
    o.preserveBoundary = false;
    TetStats stats;
    const TetMesh mesh = tetrahedralize(plc, o, noProgress(), &stats);
    const ValidationReport report = validateTetMesh(mesh, {24, 25});
    EXPECT_TRUE(report.valid()) << toJson(report).dump(1);
    EXPECT_GE(measureQuality(mesh).minDihedralDeg, 10.0);
    const auto volumes = tetVolumes(mesh);
    for (const auto& [label, expected] : voxelVolumes(scene)) EXPECT_NEAR(volumes.at(label), expected, 1e-6 * expected);
    EXPECT_LT(meanTetVolume(mesh, LabelKind::Pdl), meanTetVolume(mesh, LabelKind::Tooth));
    EXPECT_LT(meanTetVolume(mesh, LabelKind::Tooth), meanTetVolume(mesh, LabelKind::Bone));
    std::cout << "[ tetgen  ] jaw block without -Y: " << stats.tets << " tets in " << stats.seconds << " s (" << stats.switches
              << "), mean tet volume pdl " << meanTetVolume(mesh, LabelKind::Pdl) << ", tooth " << meanTetVolume(mesh, LabelKind::Tooth)
              << ", bone " << meanTetVolume(mesh, LabelKind::Bone) << " mm^3\n";
}

TEST(Tetrahedralize, NestedSpheresKeepTheirCurvedInterfaces) {
    const InterfaceComplex plc = nestedSpheresComplex(2, 0.5);
    const auto expected = complexVolumes(plc);
    for (const auto& [label, v] : expected) ASSERT_GT(v, 0) << "test complex orientation, " << labelName(label);
    TetStats stats;
    const TetMesh mesh = tetrahedralize(plc, gradedOptions(), noProgress(), &stats);
    expectGoodMesh(plc, mesh, expected, stats, "nested spheres");
}

TEST(Tetrahedralize, IsDeterministic) {
    const InterfaceComplex plc = nestedSpheresComplex(1, 1.0);
    const TetMesh a = tetrahedralize(plc, gradedOptions());
    const TetMesh b = tetrahedralize(plc, gradedOptions());
    EXPECT_EQ(a.tets, b.tets);
    EXPECT_EQ(a.labels, b.labels);
    EXPECT_EQ(a.nodes, b.nodes);
}

TEST(Tetrahedralize, UnboundedSizingStillMeetsQuality) {
    TetOptions o;  // no edge-length bounds at all
    TetStats stats;
    const TetMesh mesh = tetrahedralize(complexFromVoxels(jawBlockScene(0.5)), o, noProgress(), &stats);
    EXPECT_TRUE(validateTetMesh(mesh, {24, 25}).valid());
    EXPECT_GE(measureQuality(mesh).minDihedralDeg, 10.0);
}

TEST(Tetrahedralize, RejectsSelfIntersectingInput) {
    InterfaceComplex plc = nestedSpheresComplex(1, 1.0);
    // Move the second tooth's sphere onto the first one's PDL shell so the surfaces cross.
    const std::size_t n = plc.surface.vertices.size();
    for (std::size_t i = n - 42; i < n; ++i) plc.surface.vertices[i].x() -= 2.2;
    try {
        tetrahedralize(plc, gradedOptions());
        FAIL() << "no error for intersecting facets";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("intersect"), std::string::npos) << e.what();
    }
}

TEST(Tetrahedralize, LabelsComeFromTheInterfaceSidesAndBadComplexesAreRejected) {
    InterfaceComplex plc = nestedSpheresComplex(1, 1.0);
    InterfaceComplex noSeeds = plc;
    noSeeds.seeds.clear();
    EXPECT_THROW(tetrahedralize(noSeeds, gradedOptions()), Error);

    // Without the PDL seed of tooth 25 the labels still come out right: they are read from the
    // interface triangles' sides, not from TetGen's seed flooding (only that region's size bound
    // is lost).
    InterfaceComplex missing = plc;
    missing.seeds.erase(std::remove_if(missing.seeds.begin(), missing.seeds.end(),
                                       [](const RegionSeed& s) { return s.label == pdlLabel(25); }),
                        missing.seeds.end());
    const TetMesh m = tetrahedralize(missing, gradedOptions());
    EXPECT_NE(std::find(m.labels.begin(), m.labels.end(), pdlLabel(25)), m.labels.end());
    EXPECT_TRUE(validateTetMesh(m, {24, 25}).valid());

    // A seed in the wrong region (pdl_24's moved into tooth 24) changes nothing either.
    InterfaceComplex misplaced = plc;
    Vec3 toothSeed = Vec3::Zero();
    for (const auto& seed : plc.seeds)
        if (seed.label == toothLabel(24)) toothSeed = seed.point;
    for (auto& seed : misplaced.seeds)
        if (seed.label == pdlLabel(24)) seed.point = toothSeed;
    const TetMesh w = tetrahedralize(misplaced, gradedOptions());
    EXPECT_TRUE(validateTetMesh(w, {24, 25}).valid());
    std::map<Label, std::size_t> count;
    for (Label l : w.labels) ++count[l];
    EXPECT_EQ(count.size(), 5u);

    InterfaceComplex outsideLabel = plc;
    outsideLabel.seeds[0].label = kOutsideLabel;
    EXPECT_THROW(tetrahedralize(outsideLabel, gradedOptions()), Error);

    InterfaceComplex badSides = plc;
    badSides.sides.pop_back();
    EXPECT_THROW(tetrahedralize(badSides, gradedOptions()), Error);
}

TEST(Tetrahedralize, LabelsThatChangeBetweenTilesMesh) {
    // Issue #27's mechanism from the label field on: where labels change between tiles of the label
    // tree with no distance band there, extraction left holes, and TetGen meshed the bone into the
    // outside through them. Now the slab is closed and every region's tets fill what it encloses.
    const InterfaceComplex c = withoutCarried(extractInterfaces(tiledSlabField()));
    const TetMesh m = tetrahedralize(c, gradedOptions());
    const std::map<Label, double> enclosed = complexVolumes(c), meshed = tetVolumes(m);
    ASSERT_EQ(meshed.size(), 2u);
    for (const auto& [label, volume] : enclosed) {
        if (label == kOutsideLabel) continue;
        EXPECT_NEAR(meshed.at(label), volume, 1e-9 * volume) << labelName(label);
    }
    EXPECT_GT(meshed.at(kMandibleBoneLabel), 0.9 * 32 * 16 * 16 * std::pow(0.05, 3));
    // The adaptive extraction's carried vertices lie on no facet: refused, not handed to TetGen.
    const InterfaceComplex withCarried = extractInterfaces(tiledSlabField());
    ASSERT_FALSE(withCarried.carried.empty());
    EXPECT_THROW(tetrahedralize(withCarried, gradedOptions()), Error);
}

TEST(Tetrahedralize, TetgenDihedralBoundIsSeparateFromTheTarget) {
    const InterfaceComplex plc = nestedSpheresComplex(1, 1.0);
    TetOptions o = gradedOptions();
    o.tetgenMinDihedralDeg = 0.0;  // TetGen refines by radius-edge only; the improver aims at 10
    TetStats s;
    const TetMesh m = tetrahedralize(plc, o, noProgress(), &s);
    EXPECT_NE(s.switches.find("/0a"), std::string::npos) << s.switches;
    EXPECT_TRUE(validateTetMesh(m, {24, 25}).valid());
    EXPECT_EQ(s.belowMinDihedral, 0u) << "min dihedral " << s.minDihedralDeg;
    EXPECT_GE(s.minDihedralDeg, o.slivers.targetMinDihedralDeg);
    o.tetgenMinDihedralDeg = 70.0;
    EXPECT_THROW(tetrahedralize(plc, o), Error);
}
