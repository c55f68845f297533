// Clinical what-if edits on an analytic jaw (levelset/JawEdits.h): a box of bone with a flat crest
// at z = 0 and three capsule teeth 6 mm apart in sockets 0.1 mm wider than their roots, so every
// expected height and volume is the shape's own. Bone loss is checked by the crest's height found
// along vertical lines around a root, a healed socket by the bone's sign inside the old root and
// its volume, a PDL edit by the carve's thickness statistics.
#include "io/Edits.h"
#include "io/Error.h"
#include "levelset/JawEdits.h"
#include "levelset/ToothLongAxis.h"
#include "support/AnalyticGrids.h"

#include <openvdb/tools/Interpolation.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace jawmesh;
using openvdb::Vec3d;

namespace {

constexpr double kJawVoxelMm = 0.05;
constexpr double kRoot = 1.5, kGap = 0.1, kApex = -9.0, kTop = 3.0;
const int kUnns[] = {24, 25, 26};
double toothX(int unn) { return 6.0 * (unn - 25); }

JawLevelSets sampleAnalyticJaw() {
    JawLevelSets j;
    const Vec3d lo(-10, -4, -13), hi(10, 4, 0);
    j.bone = test::sampleSdf(
        [&](const Vec3d& p) {
            double d = test::boxSdf(p, lo, hi);
            for (int unn : kUnns) d = std::max(d, -(test::capsuleSdf(p, toothX(unn), 0, kApex, kTop, kRoot) - kGap));
            return d;
        },
        lo, hi, kJawVoxelMm);
    for (int unn : kUnns) {
        const double x = toothX(unn);
        j.teeth[unn] = test::sampleSdf([&](const Vec3d& p) { return test::capsuleSdf(p, x, 0, kApex, kTop, kRoot); },
                                       Vec3d(x - kRoot, -kRoot, kApex - kRoot), Vec3d(x + kRoot, kRoot, kTop + kRoot), kJawVoxelMm);
    }
    return j;
}

/// The jaw, sampled once: edits replace its grids rather than change them, so copies share them.
JawLevelSets analyticJaw() {
    static const JawLevelSets jaw = sampleAnalyticJaw();
    return jaw;
}

EditList editsOf(const nlohmann::json& list) { return parseEdits({{"edits", list}}, "edits.json"); }

double boneAt(const openvdb::FloatGrid& bone, const Vec3d& world) {
    return openvdb::tools::BoxSampler::sample(bone.tree(), bone.transform().worldToIndex(world));
}

/// Height of the bone's top along the vertical line through (x, y): the first crossing into bone
/// coming down from above the crest.
double boneTopAt(const openvdb::FloatGrid& bone, double x, double y) {
    for (double z = 1.0; z > -12.0; z -= 0.005)
        if (boneAt(bone, Vec3d(x, y, z)) < 0) return z;
    return -100;
}

/// The bone's top at 12 azimuths around a tooth, 1 mm out from its socket wall.
std::vector<double> crestRing(const openvdb::FloatGrid& bone, int unn) {
    std::vector<double> tops;
    for (int k = 0; k < 12; ++k) {
        const double phi = 2 * M_PI * k / 12, r = kRoot + kGap + 1.0;
        tops.push_back(boneTopAt(bone, toothX(unn) + r * std::cos(phi), r * std::sin(phi)));
    }
    return tops;
}

/// Voxels of the jaw's box inside `after` but not `before` (every voxel, tiles included: a sign
/// carried wrongly through an inactive region shows here).
std::size_t voxelsTurnedInside(const openvdb::FloatGrid& before, const openvdb::FloatGrid& after) {
    const openvdb::CoordBBox box(openvdb::Coord(-210, -90, -270), openvdb::Coord(210, 90, 30));
    auto a = before.getConstAccessor(), b = after.getConstAccessor();
    std::size_t n = 0;
    for (auto it = box.begin(); it; ++it) n += a.getValue(*it) >= 0 && b.getValue(*it) < 0;
    return n;
}

}  // namespace

TEST(JawEdits, ToothAxesPointFromTheRootToTheCrown) {
    // Off the bone's band its value is the band's width (0.15 mm), under the contact distance: the
    // crown must not count as touching bone, or half the axes point down.
    const JawLevelSets jaw = analyticJaw();
    for (int unn : kUnns) {
        const LongAxis a = toothLongAxis(*jaw.teeth.at(unn), *jaw.bone, 0.2, nullptr);
        EXPECT_GT(a.axis.dot(Vec3d(0, 0, 1)), 0.999) << "tooth " << unn;
        EXPECT_NEAR(a.lateralOf(Vec3d(toothX(unn), 0, 0)), 0.0, 0.01) << "tooth " << unn;
    }
}

TEST(JawEdits, BoneLossLowersTheCrestAroundTheListedTeethByItsDepth) {
    JawLevelSets jaw = analyticJaw();
    const auto before = jaw.bone;
    CarveOptions carve;
    const nlohmann::json record =
        applyEdits(editsOf({{{"op", "bone_loss"}, {"teeth", {24}}, {"depth_mm", 2.0}}}), jaw, carve);
    // All around tooth 24, facing tooth 25 too, the crest is 2 mm lower.
    for (double top : crestRing(*before, 24)) EXPECT_NEAR(top, 0.0, 0.01);
    const auto ring = crestRing(*jaw.bone, 24);
    for (int k = 0; k < 12; ++k) EXPECT_NEAR(ring[k], -2.0, 0.05) << "azimuth " << 30 * k << " deg";
    // Tooth 25's crest keeps its height away from 24; facing it, the septum slopes up to it.
    const auto ring25 = crestRing(*jaw.bone, 25);
    for (int k : {10, 11, 0, 1, 2}) EXPECT_NEAR(ring25[k], 0.0, 0.01) << "azimuth " << 30 * k << " deg";
    EXPECT_GT(ring25[6], -1.5);
    EXPECT_LT(ring25[6], 0.0);
    EXPECT_NEAR(boneTopAt(*jaw.bone, 9.5, 0), 0.0, 0.01);
    // The socket below the new crest keeps its wall and floor: the fill keeps them from dropping.
    for (double z : {-3.0, -5.0, -8.0})
        EXPECT_NEAR(boneAt(*jaw.bone, Vec3d(toothX(24) + kRoot + kGap, 0, z)), boneAt(*before, Vec3d(toothX(24) + kRoot + kGap, 0, z)), 1e-4);
    EXPECT_NEAR(boneAt(*jaw.bone, Vec3d(toothX(24), 0, kApex - kRoot - kGap)), 0.0, 0.01);
    // Bone is only taken away.
    EXPECT_EQ(voxelsTurnedInside(*before, *jaw.bone), 0u);
    // The record measures the same drop on the grids.
    const auto& t = record.at("applied").at(0).at("teeth").at(0);
    EXPECT_EQ(t.at("tooth"), 24);
    EXPECT_NEAR(t.at("crest_drop_mm").get<double>(), 2.0, 0.1);
}

TEST(JawEdits, AngularDefectIsAFunnelOnOneSideOfTheRoot) {
    JawLevelSets jaw = analyticJaw();
    const auto before = jaw.bone;
    CarveOptions carve;
    const nlohmann::json record = applyEdits(
        editsOf({{{"op", "bone_loss"}, {"tooth", 25}, {"side", "mesial"}, {"depth_mm", 3.0}, {"width_mm", 1.5}}}), jaw, carve);
    const auto& e = record.at("applied").at(0);
    // Mesial of 25 is towards 24 (the midline lies between 24 and 25): -x here.
    EXPECT_NEAR(e.at("side_direction")[0].get<double>(), -1.0, 1e-3);
    // The funnel: 3 mm deep at the root, none 1.5 mm out from it; nothing on the other sides.
    const double root = kRoot + kGap;
    for (double out : {0.2, 0.6, 1.0}) {
        const double expected = -3.0 * (1.0 - (out + kGap) / 1.5);
        EXPECT_NEAR(boneTopAt(*jaw.bone, -(root + out), 0), expected, 0.1) << out << " mm out";
    }
    EXPECT_NEAR(boneTopAt(*jaw.bone, -(root + 1.6), 0), 0.0, 0.01);
    EXPECT_NEAR(boneTopAt(*jaw.bone, root + 0.2, 0), 0.0, 0.01);
    EXPECT_NEAR(boneTopAt(*jaw.bone, 0, root + 0.2), 0.0, 0.01);
    EXPECT_EQ(voxelsTurnedInside(*before, *jaw.bone), 0u);
    EXPECT_GT(e.at("crest_drop_at_side_mm").get<double>(), 1.5);
}

TEST(JawEdits, HealedExtractionFillsTheSocketWithBoneUpToTheCrest) {
    JawLevelSets jaw = analyticJaw();
    const auto before = jaw.bone;
    CarveOptions carve;
    const nlohmann::json record =
        applyEdits(editsOf({{{"op", "extract"}, {"tooth", 25}, {"socket", "healed"}}}), jaw, carve);
    EXPECT_FALSE(jaw.teeth.count(25));
    EXPECT_EQ(jaw.teeth.size(), 2u);
    // Inside the old root and its gap, below the crest: bone. Above the crest: still outside.
    for (double z : {-0.3, -4.0, -8.5}) {
        EXPECT_LT(boneAt(*jaw.bone, Vec3d(0, 0, z)), 0) << z;
        EXPECT_LT(boneAt(*jaw.bone, Vec3d(kRoot + 0.5 * kGap, 0, z)), 0) << z;
    }
    EXPECT_GT(boneAt(*jaw.bone, Vec3d(0, 0, 0.3)), 0);
    // The crest over the old socket is flat with its surroundings, the other sockets untouched.
    EXPECT_NEAR(boneTopAt(*jaw.bone, 0, 0), 0.0, 0.06);
    EXPECT_NEAR(boneAt(*jaw.bone, Vec3d(toothX(24) + kRoot, 0, -4)), boneAt(*before, Vec3d(toothX(24) + kRoot, 0, -4)), 1e-6);
    // Filled: the socket below the crest, a cylinder and a half ball of radius root + gap.
    const double R = kRoot + kGap;
    const double socket = M_PI * R * R * (0.0 - kApex) + 2.0 / 3.0 * M_PI * R * R * R;
    const auto& e = record.at("applied").at(0);
    EXPECT_NEAR(e.at("filled_volume_mm3").get<double>(), socket, 0.03 * socket);
    EXPECT_NEAR(e.at("fill_level_mm").get<double>() + e.at("axis").at("origin")[2].get<double>(), 0.0, 0.06);
}

TEST(JawEdits, PdlThicknessEditSetsOneToothsPdl) {
    JawLevelSets jaw = analyticJaw();
    CarveOptions carve;
    applyEdits(editsOf({{{"op", "pdl_thickness"}, {"tooth", 24}, {"thickness_mm", 0.3}}}), jaw, carve);
    CarveSummary summary;
    carveJaw(Jaw::Mandible, *jaw.bone, jaw.teeth, carve, summary);
    for (const auto& t : summary.teeth) {
        const double target = t.unn == 24 ? 0.3 : 0.2;
        EXPECT_NEAR(t.thickness.mean, target, 0.015) << "tooth " << t.unn;
        EXPECT_GT(t.thickness.p05, target - 0.03) << "tooth " << t.unn;
        EXPECT_LT(t.thickness.p95, target + 0.03) << "tooth " << t.unn;
    }
    EXPECT_EQ(toJson(carve).at("tooth_pdl_mm").at("24").at("mid_root"), 0.3);
}

TEST(JawEdits, AreDeterministic) {
    const auto edits = editsOf({{{"op", "bone_loss"}, {"teeth", {24}}, {"depth_mm", 1.5}},
                                {{"op", "extract"}, {"tooth", 26}, {"socket", "healed"}},
                                {{"op", "implant"}, {"tooth", 25}, {"diameter_mm", 3.0}, {"length_mm", 8.0}, {"body", "screw"}}});
    JawLevelSets a = analyticJaw(), b = analyticJaw();
    CarveOptions ca, cb;
    const auto withoutTimes = [](nlohmann::json record) {
        for (auto& e : record.at("applied")) e.erase("seconds");
        return record;
    };
    EXPECT_EQ(withoutTimes(applyEdits(edits, a, ca)), withoutTimes(applyEdits(edits, b, cb)));
    using Grids = std::pair<openvdb::FloatGrid::ConstPtr, openvdb::FloatGrid::ConstPtr>;
    for (const auto& [ga, gb] : {Grids(a.bone, b.bone), Grids(a.teeth.at(25), b.teeth.at(25))}) {
        ASSERT_EQ(ga->activeVoxelCount(), gb->activeVoxelCount());
        auto acc = gb->getConstAccessor();
        for (auto it = ga->cbeginValueOn(); it; ++it) ASSERT_EQ(*it, acc.getValue(it.getCoord()));
    }
}

TEST(JawEdits, RefuseWhatCannotApplyNamingTheEntry) {
    const auto refused = [](const nlohmann::json& list) {
        JawLevelSets jaw = analyticJaw();
        CarveOptions carve;
        try {
            applyEdits(editsOf(list), jaw, carve);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(refused({{{"op", "extract"}, {"tooth", 24}}, {{"op", "extract"}, {"tooth", 30}}}).find("edits.json: edits[1]: tooth 30 is not in this jaw"),
              std::string::npos);
    const std::string deep = refused({{{"op", "bone_loss"}, {"teeth", {25}}, {"depth_mm", 9.5}}});
    EXPECT_NE(deep.find("edits.json: edits[0]"), std::string::npos) << deep;
    EXPECT_NE(deep.find("of it in bone"), std::string::npos) << deep;
    // The box is 13 mm deep under its crest: a 14 mm implant would leave it.
    const std::string longer = refused({{{"op", "implant"}, {"tooth", 25}, {"diameter_mm", 3.0}, {"length_mm", 14.0}}});
    EXPECT_NE(longer.find("edits.json: edits[0]: a 14.0 mm implant along tooth 25's axis leaves the bone"), std::string::npos)
        << longer;
}

TEST(JawEdits, ImplantReplacesTheToothFusedToTheBoneWithItsBodysVolume) {
    JawLevelSets jaw = analyticJaw();
    CarveOptions carve;
    const nlohmann::json record = applyEdits(
        editsOf({{{"op", "implant"}, {"tooth", 25}, {"diameter_mm", 3.0}, {"length_mm", 10.0}}}), jaw, carve);
    const auto& e = record.at("applied")[0];
    EXPECT_EQ(carve.implants, std::set<int>{25});
    EXPECT_NEAR(e.at("crest_mm").get<double>() + e.at("axis").at("origin")[2].get<double>(), 0.0, 0.06);
    CarveSummary summary;
    const LabelField field = carveJaw(Jaw::Mandible, *jaw.bone, jaw.teeth, carve, summary);
    EXPECT_TRUE(field.distances.count(implantLabel(25)));
    EXPECT_FALSE(field.distances.count(toothLabel(25)) || field.distances.count(pdlLabel(25)));
    // Voxels of the implant below the platform (the crest, z = 0) against pi r^2 L; faces with the
    // bone all round the body (fused), none with the PDLs or teeth beside it.
    const double voxel3 = std::pow(kJawVoxelMm, 3);
    std::size_t below = 0, boneFaces = 0, otherFaces = 0;
    auto labels = field.labels->getConstAccessor();
    const openvdb::CoordBBox box(openvdb::Coord(-60, -60, -260), openvdb::Coord(60, 60, 80));
    for (auto it = box.begin(); it; ++it) {
        if (labels.getValue(*it) != implantLabel(25)) continue;
        below += field.labels->transform().indexToWorld(*it).z() < 0;
        for (const openvdb::Coord& d : {openvdb::Coord(1, 0, 0), openvdb::Coord(-1, 0, 0), openvdb::Coord(0, 1, 0),
                                        openvdb::Coord(0, -1, 0), openvdb::Coord(0, 0, -1)}) {
            const Label other = labels.getValue(*it + d);
            boneFaces += other == kMandibleBoneLabel;
            otherFaces += other != kMandibleBoneLabel && other != kOutsideLabel && other != implantLabel(25);
        }
    }
    const double body = M_PI * 1.5 * 1.5 * 10.0;
    EXPECT_NEAR(e.at("body_volume_mm3").get<double>(), body, 1e-9);
    EXPECT_NEAR(double(below) * voxel3, body, 0.02 * body);
    EXPECT_GT(boneFaces, 10000u);
    EXPECT_EQ(otherFaces, 0u);
    for (const auto& t : summary.teeth) EXPECT_EQ(t.implant, t.unn == 25) << "tooth " << t.unn;
    EXPECT_EQ(summary.toothBoneContacts, 0u);
}
