// runTetgenInGroups (tet/TetgenGroups.h): two runs over two groups of regions give one conformal
// mesh whose regions fill exactly what one run's do, the same whatever the thread count.
#include "io/Labels.h"
#include "tet/LabelFromSides.h"
#include "tet/TetTestComplexes.h"
#include "tet/TetgenGroups.h"
#include "tet/Tetrahedralize.h"
#include "tet/ValidateTetMesh.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <set>

using namespace jawmesh;
using namespace jawmesh::test;

namespace {

TetgenRun sphereRun(const InterfaceComplex& plc) {
    TetOptions o;
    o.pdlEdgeMm = 0.3;
    o.toothEdgeMm = 0.6;
    o.boneEdgeMm = 1.0;
    TetgenRun run;
    run.switches = "pzQAq1.5/10aYMO3/7";
    for (const RegionSeed& s : plc.seeds) {
        const LabelKind k = labelKind(s.label);
        run.seedVolumeBoundsMm3.push_back(
            tetVolumeForEdge(k == LabelKind::Pdl ? o.pdlEdgeMm : k == LabelKind::Tooth ? o.toothEdgeMm : o.boneEdgeMm));
    }
    return run;
}

std::map<Label, double> volumesOf(const TetMesh& m) {
    std::map<Label, double> v;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        const Tet& e = m.tets[t];
        const Vec3& a = m.nodes[std::size_t(e[0])];
        v[m.labels[t]] +=
            (m.nodes[std::size_t(e[1])] - a).dot((m.nodes[std::size_t(e[2])] - a).cross(m.nodes[std::size_t(e[3])] - a)) / 6.0;
    }
    return v;
}

TetgenMesh groupedIn(int threads, const InterfaceComplex& plc, const TetgenRun& run) {
    tbb::task_arena arena(threads);
    TetgenMesh raw;
    std::uint64_t peak = 0;
    arena.execute([&] { raw = runTetgenInGroups(plc, run, true, false, peak); });
    return raw;
}

TEST(TetgenGroups, SplitTheRegionsInTwoNonEmptyGroupsByTheirTriangles) {
    const InterfaceComplex plc = nestedSpheresComplex();
    const std::map<Label, int> groups = tetgenGroups(plc);
    std::set<Label> labels;
    for (const auto& s : plc.sides)
        for (Label l : s)
            if (l != kOutsideLabel) labels.insert(l);
    std::set<Label> grouped;
    std::size_t load[2] = {}, largest = 0;
    for (const auto& [label, g] : groups) {
        grouped.insert(label);
        ASSERT_TRUE(g == 0 || g == 1);
        std::size_t n = 0;
        for (const auto& s : plc.sides) n += std::size_t(s[0] == label) + std::size_t(s[1] == label);
        load[g] += n;
        largest = std::max(largest, n);
    }
    EXPECT_EQ(grouped, labels);
    EXPECT_GT(load[0], 0u);
    EXPECT_GT(load[1], 0u);
    // largest first to the lighter group: the two differ by no more than the largest region
    EXPECT_LE(std::max(load[0], load[1]) - std::min(load[0], load[1]), largest);
    EXPECT_EQ(groups, tetgenGroups(plc));
}

TEST(TetgenGroups, TwoRunsMakeOneConformalMeshOfTheSameRegionsWhateverTheThreads) {
    const InterfaceComplex plc = nestedSpheresComplex();
    const TetgenRun run = sphereRun(plc);
    TetgenMesh whole = runTetgen(plc, run);
    labelFromSides(plc, whole);
    keepLabeled(whole.mesh);

    TetgenMesh grouped = groupedIn(2, plc, run);
    // every input triangle is a face of the merged mesh, each once
    std::set<std::array<std::int32_t, 3>> facets(grouped.facets.begin(), grouped.facets.end());
    EXPECT_EQ(facets.size(), grouped.facets.size());
    for (const Tri& f : plc.surface.triangles) {
        std::array<std::int32_t, 3> key = f;
        std::sort(key.begin(), key.end());
        EXPECT_TRUE(facets.count(key)) << "input triangle lost";
    }
    EXPECT_EQ(std::vector<Vec3>(grouped.mesh.nodes.begin(), grouped.mesh.nodes.begin() + std::ptrdiff_t(plc.surface.vertices.size())),
              plc.surface.vertices);
    // labeled already, as labelling the union from its sides labels it (which throws when a
    // region's sides disagree)
    const std::vector<Label> asReturned = grouped.mesh.labels;
    labelFromSides(plc, grouped);
    EXPECT_EQ(grouped.mesh.labels, asReturned);
    keepLabeled(grouped.mesh);
    const ValidationReport report = validateTetMesh(grouped.mesh, {});
    EXPECT_TRUE(report.valid()) << toJson(report).dump(1);

    // the same regions, filled exactly: both tile the volumes the triangles enclose
    const auto a = volumesOf(whole.mesh), b = volumesOf(grouped.mesh), c = complexVolumes(plc);
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [label, v] : c) {
        ASSERT_TRUE(b.count(label)) << labelName(label);
        EXPECT_NEAR(b.at(label), v, 1e-9 * v) << labelName(label);
        EXPECT_NEAR(a.at(label), v, 1e-9 * v) << labelName(label);
    }

    const TetgenMesh serial = groupedIn(1, plc, run);
    TetgenMesh parallel = groupedIn(2, plc, run);
    EXPECT_EQ(serial.mesh.nodes, parallel.mesh.nodes);
    EXPECT_EQ(serial.mesh.tets, parallel.mesh.tets);
    EXPECT_EQ(serial.mesh.labels, parallel.mesh.labels);
    EXPECT_EQ(serial.facets, parallel.facets);
}

}  // namespace
