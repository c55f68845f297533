// regionSurfaces(): closed, outward, volume-consistent boundaries of each region; files written.
#include "io/Error.h"
#include "io/MeshIO.h"
#include "io/PolyWriter.h"
#include "support/TestData.h"
#include "tet/GridTetMesh.h"
#include "tet/RegionSurfaces.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>

using namespace jawmesh;
using namespace jawmesh::test;

namespace {
TetMesh twoToothGrid() {
    return gridTetMesh(8, 4, 4, 0.5, [](const Vec3& p) {
        const bool column = p.y() > 0.5 && p.y() < 1.5 && p.z() > 0.5;
        if (column && p.x() > 0.5 && p.x() < 1.5) return toothLabel(24);
        if (column && p.x() > 2.5 && p.x() < 3.5) return toothLabel(25);
        if (p.y() > 0.5 && p.y() < 1.5 && p.x() > 2.0 && p.x() < 4.0 && p.z() > 0.5) return pdlLabel(25);
        return kMandibleBoneLabel;
    });
}
}  // namespace

TEST(RegionSurfaces, ClosedOutwardAndMatchRegionVolumes) {
    const TetMesh m = twoToothGrid();
    std::map<Label, double> volume;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        const Tet& e = m.tets[t];
        const Vec3& a = m.nodes[static_cast<std::size_t>(e[0])];
        volume[m.labels[t]] += (m.nodes[static_cast<std::size_t>(e[1])] - a)
                                   .dot((m.nodes[static_cast<std::size_t>(e[2])] - a).cross(m.nodes[static_cast<std::size_t>(e[3])] - a)) / 6.0;
    }
    const auto surfaces = regionSurfaces(m);
    ASSERT_EQ(surfaces.size(), volume.size());
    for (const auto& [label, s] : surfaces) {
        // Closed and consistently oriented: every directed edge has its reverse exactly once.
        std::map<std::pair<int, int>, int> directed;
        for (const Tri& t : s.triangles)
            for (int k = 0; k < 3; ++k) ++directed[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
        for (const auto& [edge, count] : directed) {
            EXPECT_EQ(count, 1) << labelName(label);
            EXPECT_EQ(directed.count({edge.second, edge.first}), 1u) << labelName(label);
        }
        EXPECT_NEAR(signedVolume(s), volume.at(label), 1e-9 * volume.at(label)) << labelName(label);
    }
}

TEST(RegionSurfaces, WritesOneStlPerRegion) {
    const auto dir = scratchDir("region-surfaces");
    const auto paths = writeRegionSurfaces(twoToothGrid(), dir.string());
    EXPECT_EQ(paths.size(), 4u);
    for (const char* name : {"bone.stl", "tooth_24.stl", "tooth_25.stl", "pdl_25.stl"})
        EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
    EXPECT_THROW(regionSurfaceFileName(kOutsideLabel), Error);
}

TEST(RegionSurfaces, MeshInterfacesGiveTheComplexBackOrientedIntoTheSmallerLabel) {
    const TetMesh m = twoToothGrid();
    const InterfaceComplex c = meshInterfaces(m);
    const auto surfaces = regionSurfaces(m);
    std::size_t faces = 0;
    for (const auto& [label, s] : surfaces) faces += s.triangles.size();
    std::size_t interior = 0;  // interface faces appear in two region surfaces, the outer ones in one
    for (const auto& side : c.sides) {
        EXPECT_LT(side[0], side[1]);
        interior += side[0] != kOutsideLabel;
    }
    EXPECT_EQ(c.surface.triangles.size() + interior, faces);
    EXPECT_TRUE(c.seeds.empty());
    // every region's boundary taken from the complex encloses the region's volume (orientation)
    for (const auto& [label, s] : surfaces)
        EXPECT_NEAR(signedVolume(regionBoundary(c, label)), signedVolume(s), 1e-9) << labelName(label);
    // only interface nodes are kept
    std::vector<char> used(c.surface.vertices.size(), 0);
    for (const Tri& t : c.surface.triangles)
        for (auto v : t) used[std::size_t(v)] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 1), std::ptrdiff_t(c.surface.vertices.size()));
    EXPECT_LT(c.surface.vertices.size(), m.nodes.size());
}
