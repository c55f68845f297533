// rasterizeSection() and the report's section planes on a grid mesh whose labels are known at
// every point: pixels carry the label of the cube under their centre, the planes go through the
// tooth along its axis and across the PDLs.
#include "filters/CrossSection.h"
#include "io/Error.h"
#include "support/SyntheticJaw.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

using namespace jawmesh;
using namespace jawmesh::test;

namespace {
/// Label of the synthetic jaw's cell holding p (labels are per grid cube), kOutsideLabel if none.
class CellLabels {
public:
    explicit CellLabels(const TetMesh& m) {
        for (std::size_t t = 0; t < m.tets.size(); ++t) {
            Vec3 c = Vec3::Zero();
            for (std::int32_t v : m.tets[t]) c += m.nodes[static_cast<std::size_t>(v)] / 4.0;
            labels_[key(c)] = m.labels[t];
        }
    }
    Label at(const Vec3& p) const {
        const auto it = labels_.find(key(p));
        return it == labels_.end() ? kOutsideLabel : it->second;
    }

private:
    static std::array<long, 3> key(const Vec3& p) {
        return {std::lround(std::floor(p.x() / kJawCellMm)), std::lround(std::floor(p.y() / kJawCellMm)), std::lround(std::floor(p.z() / kJawCellMm))};
    }
    std::map<std::array<long, 3>, Label> labels_;
};
}  // namespace

TEST(CrossSection, PixelsTakeTheLabelUnderTheirCentre) {
    const TetMesh m = syntheticJawMesh();
    SectionPlane plane;  // vertical plane y = 2.05 (inside cells, off their faces), x right, z up
    plane.centreMm = Vec3(3.6, 2.05, 2.5);
    plane.right = Vec3::UnitX();
    plane.up = Vec3::UnitZ();
    plane.widthMm = 7.6;
    plane.heightMm = 5.4;
    const SectionRaster r = rasterizeSection(m, plane, 0.07);
    const CellLabels cells(m);
    ASSERT_EQ(r.width, static_cast<int>(std::ceil(7.6 / 0.07)));
    int checked = 0, wrong = 0, edges = 0;
    for (int y = 0; y < r.height; y += 3)
        for (int x = 0; x < r.width; x += 3) {
            const Vec3 p = plane.centreMm + ((x + 0.5) * 0.07 - 3.8) * plane.right + (2.7 - (y + 0.5) * 0.07) * plane.up;
            // Pixels within a hair of a cell face may take either side's label.
            const auto nearFace = [](double v) { return std::abs(v / kJawCellMm - std::round(v / kJawCellMm)) < 0.01; };
            if (nearFace(p.x()) || nearFace(p.z())) continue;
            const Label expected = cells.at(p);
            ++checked;
            wrong += r.label[static_cast<std::size_t>(y) * static_cast<std::size_t>(r.width) + static_cast<std::size_t>(x)] != expected;
            edges += r.edge[static_cast<std::size_t>(y) * static_cast<std::size_t>(r.width) + static_cast<std::size_t>(x)];
        }
    EXPECT_GT(checked, 800);
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(edges, 0);
    EXPECT_THROW(rasterizeSection(m, plane, 0), Error);
    plane.up = Vec3(0, 1, 1);
    EXPECT_THROW(rasterizeSection(m, plane, 0.1), Error);
}

TEST(CrossSection, ToothPlaneFollowsTheToothAxisAndArchPlaneCutsThePdls) {
    const TetMesh m = syntheticJawMesh();
    const auto tooth = toothSectionPlane(m, 24);
    ASSERT_TRUE(tooth.has_value());
    EXPECT_NEAR(tooth->up.z(), 1.0, 1e-6);  // long axis is z, occlusal (away from the PDL) is +z
    EXPECT_NEAR(tooth->centreMm.x(), 2.0, 1e-6);
    EXPECT_NEAR(tooth->centreMm.z(), 2.8, 1e-6);  // middle of the tooth (0.8 .. 4.8)
    EXPECT_NEAR(tooth->heightMm, 1.3 * 4.0, 0.01);  // the grid's Kuhn tets tilt the axis by ~1e-3
    EXPECT_NEAR(std::abs(tooth->right.y()), 1.0, 1e-6);  // across the arch (which runs along x here)
    EXPECT_FALSE(toothSectionPlane(m, 30).has_value());

    const auto arch = archSectionPlane(m);
    ASSERT_TRUE(arch.has_value());
    EXPECT_NEAR(std::abs(arch->right.cross(arch->up).z()), 1.0, 1e-6);  // horizontal
    EXPECT_GT(arch->centreMm.z(), 0.6);
    EXPECT_LT(arch->centreMm.z(), kJawCrestZ);  // at the height of the PDLs
    const SectionRaster r = rasterizeSection(m, *arch, 0.05);
    std::map<Label, int> seen;
    for (Label l : r.label) ++seen[l];
    for (Label l : {kMandibleBoneLabel, toothLabel(24), toothLabel(25), pdlLabel(24), pdlLabel(25)}) EXPECT_GT(seen[l], 50) << l;
}
