// Gap carving on a small synthetic jaw built as analytic grids: a box "bone" (crest at z = 0) with
// capsule "teeth" in sockets of different fits (gap wider than the widening, exact fit, tooth
// overlapping bone), two teeth 0.2 mm apart, an impacted tooth and a floating one.
#include "io/Error.h"
#include "levelset/CarveGaps.h"
#include "levelset/CarveMeasure.h"
#include "levelset/LabelFieldIO.h"
#include "support/AnalyticGrids.h"
#include "support/TestData.h"

#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/SignedFloodFill.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

using namespace jawmesh;
using openvdb::Coord;
using openvdb::Vec3d;

namespace {

constexpr double kVoxel = 0.05;

openvdb::FloatGrid::Ptr sample(const test::Sdf& f, Vec3d lo, Vec3d hi, double halfWidth = 3.0) {
    return test::sampleSdf(f, lo, hi, kVoxel, halfWidth);
}

using test::boxSdf;

/// Vertical capsule at (x, 0) from z0 to z1.
double capsule(const Vec3d& p, double x, double z0, double z1, double r) { return test::capsuleSdf(p, x, 0, z0, z1, r); }

struct ToothShape {
    int unn;
    double x, z0, z1, r, socketGap;  // socketGap < 0: bone overlaps the tooth (no socket cut)
    bool sphere = false;
};

// Crest at z = 0; bone box x [-6, 6], y [-3, 3], z [-9, 0].
const std::vector<ToothShape> kTeeth = {
    {24, -2.0, -5.0, 3.0, 1.2, 0.25},   // socket 0.25 mm wider than the root: gap to bridge
    {25, 0.8, -5.0, 3.0, 1.2, -1.0},    // bone overlaps the root: teeth win
    {26, 3.4, -5.0, 3.0, 1.2, 0.0},     // exact fit, 0.2 mm from tooth 25
    {20, -4.6, -7.0, -7.0, 0.9, 0.0},   // impacted (a ball inside bone)
    {30, 5.3, 1.2, 3.0, 0.5, 0.0},      // floating above the bone, 0.2 mm from tooth 26
};

double toothSdf(const ToothShape& t, const Vec3d& p) { return capsule(p, t.x, t.z0, t.z1, t.r); }

struct Jaw3 {
    openvdb::FloatGrid::Ptr bone;
    std::map<int, openvdb::FloatGrid::ConstPtr> teeth;
};

const Jaw3& syntheticJaw() {
    static const Jaw3 jaw = [] {
        Jaw3 j;
        const Vec3d lo(-6, -3, -9), hi(6, 3, 0);
        j.bone = sample(
            [&](const Vec3d& p) {
                double d = boxSdf(p, lo, hi);
                for (const auto& t : kTeeth)
                    if (t.socketGap >= 0 && t.unn != 20) d = std::max(d, -(toothSdf(t, p) - t.socketGap));
                return d;
            },
            lo, hi);
        for (const auto& t : kTeeth)
            j.teeth[t.unn] = sample([&](const Vec3d& p) { return toothSdf(t, p); }, Vec3d(t.x - t.r, -t.r, t.z0 - t.r),
                                    Vec3d(t.x + t.r, t.r, t.z1 + t.r));
        return j;
    }();
    return jaw;
}

struct Carved {
    LabelField field;
    CarveSummary summary;
};

const Carved& carvedDefault() {
    static const Carved c = [] {
        Carved r;
        const auto& j = syntheticJaw();
        r.field = carveJaw(Jaw::Mandible, *j.bone, j.teeth, CarveOptions(), r.summary);
        return r;
    }();
    return c;
}

const ToothCarveSummary& toothSummary(const CarveSummary& s, int unn) {
    for (const auto& t : s.teeth)
        if (t.unn == unn) return t;
    throw Error("no summary for tooth " + std::to_string(unn));
}

Label labelAt(const LabelField& f, const Vec3d& world) {
    return f.labels->tree().getValue(f.labels->transform().worldToIndexNodeCentered(world));
}

int groupOf(Label l) {
    const auto k = labelKind(l);
    return (k == LabelKind::Tooth || k == LabelKind::Pdl) ? labelUnn(l) : 0;
}

}  // namespace

TEST(Carve, PdlThicknessMatchesTargetOnEveryRootedTooth) {
    const auto& c = carvedDefault();
    for (int unn : {24, 25, 26, 20}) {
        const auto& t = toothSummary(c.summary, unn).thickness;
        SCOPED_TRACE("tooth " + std::to_string(unn));
        ASSERT_GT(t.samples, 200u);
        EXPECT_NEAR(t.mean, 0.2, 0.01);
        EXPECT_GE(t.p05, 0.17);
        EXPECT_LE(t.p95, 0.23);
    }
}

TEST(Carve, RadialProfileThroughTheRoot) {
    // Along +x from the axis of the exact-fit tooth 26 at mid-root: tooth, PDL (e inside the
    // input surface, w outside), then bone.
    const auto& f = carvedDefault().field;
    const double r = 1.2, e = 0.1, w = 0.1;
    const Vec3d axis(3.4, 0, -2.5);
    auto at = [&](double d) { return labelAt(f, axis + Vec3d(0, d, 0)); };
    EXPECT_EQ(at(r - e - 2 * kVoxel), toothLabel(26));
    EXPECT_EQ(at(r - e / 2), pdlLabel(26));
    EXPECT_EQ(at(r + w / 2), pdlLabel(26));
    EXPECT_EQ(at(r + w + 2 * kVoxel), boneLabel(Jaw::Mandible));
    // The bridged socket of tooth 24 (0.25 mm gap): PDL then bone, no void.
    const Vec3d axis24(-2.0, 0, -2.5);
    for (double d = r - e / 2; d < r + 0.6; d += kVoxel / 2) {
        const Label l = labelAt(f, axis24 + Vec3d(0, d, 0));
        EXPECT_NE(l, kOutsideLabel) << "void at " << d << " mm from the axis of tooth 24";
    }
}

TEST(Carve, CrownKeepsItsInputShape) {
    const auto& f = carvedDefault().field;
    const auto& xf = f.labels->transform();
    std::size_t checked = 0;
    for (const auto& t : kTeeth) {
        if (t.unn == 20) continue;
        for (int i = int((t.x - t.r - 0.3) / kVoxel); i <= int((t.x + t.r + 0.3) / kVoxel); ++i)
            for (int j = int(-(t.r + 0.3) / kVoxel); j <= int((t.r + 0.3) / kVoxel); ++j)
                for (int k = int(0.5 / kVoxel); k <= int(t.z1 / kVoxel); ++k) {  // above the crest + gap bridge
                    const Vec3d p = xf.indexToWorld(Coord(i, j, k));
                    const double d = toothSdf(t, p);
                    // Stay clear of the bisector with the neighbouring tooth 25/26.
                    bool nearOther = false;
                    for (const auto& o : kTeeth)
                        if (o.unn != t.unn && std::abs(toothSdf(o, p) - d) < 0.2) nearOther = true;
                    if (nearOther || std::abs(d) < kVoxel / 2) continue;
                    const Label l = f.labels->tree().getValue(Coord(i, j, k));
                    EXPECT_EQ(l == toothLabel(t.unn), d < 0) << "tooth " << t.unn << " at " << p;
                    ++checked;
                }
    }
    EXPECT_GT(checked, 10000u);
}

TEST(Carve, TeethAndPdlsNeverTouchAndToothMeetsBoneOnlyThroughPdl) {
    const auto& f = carvedDefault().field;
    const auto& tree = f.labels->tree();
    auto acc = f.labels->getConstAccessor();
    std::size_t contacts = 0, boneTouches = 0, voxels = 0;
    for (auto it = tree.cbeginValueOn(); it; ++it) {
        if (!it.isVoxelValue()) continue;
        const int g = groupOf(*it);
        if (!g) continue;
        ++voxels;
        const Coord p = it.getCoord();
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const Label m = acc.getValue(p.offsetBy(dx, dy, dz));
                    const int h = groupOf(m);
                    if (h && h != g) ++contacts;
                    if (labelKind(*it) == LabelKind::Tooth && m == boneLabel(Jaw::Mandible)) ++boneTouches;
                }
    }
    EXPECT_GT(voxels, 1000u);
    EXPECT_EQ(contacts, 0u);
    EXPECT_EQ(boneTouches, 0u);
}

TEST(Carve, ImpactedToothGetsClosedEnvelopeAndFloatingToothNone) {
    const auto& c = carvedDefault();
    const auto& impacted = toothSummary(c.summary, 20);
    EXPECT_TRUE(impacted.impacted);
    EXPECT_GT(impacted.pdlVolumeMm3, 0.0);
    const auto& floating = toothSummary(c.summary, 30);
    EXPECT_EQ(floating.pdlVolumeMm3, 0.0);
    const bool warned = std::any_of(c.summary.warnings.begin(), c.summary.warnings.end(),
                                    [](const std::string& w) { return w.find("tooth 30") != std::string::npos; });
    EXPECT_TRUE(warned);
    EXPECT_FALSE(toothSummary(c.summary, 24).impacted);
    // Root / crown split: about half of each rooted capsule is in the socket.
    EXPECT_GT(toothSummary(c.summary, 26).rootAreaFraction, 0.3);
    EXPECT_LT(toothSummary(c.summary, 26).rootAreaFraction, 0.8);
}

TEST(Carve, DistancesAreConsistentWithLabels) {
    const auto& f = carvedDefault().field;
    std::size_t checked = 0;
    for (const auto& [label, grid] : f.distances) {
        auto acc = grid->getConstAccessor();
        for (auto it = f.labels->tree().cbeginValueOn(); it; ++it) {
            if (!it.isVoxelValue()) continue;
            const Coord c = it.getCoord();
            if ((c.x() + c.y() + c.z()) % 7) continue;  // a deterministic subsample
            const bool inside = acc.getValue(c) < 0;
            if (inside != (*it == label)) {
                ADD_FAILURE() << labelName(label) << " distance " << acc.getValue(c) << " vs label " << *it << " at " << c;
                return;
            }
            ++checked;
        }
    }
    EXPECT_GT(checked, 10000u);
}

// A kept PDL (a label map's, issue #23): the bone leaves the PDL out, and the carve keeps the gap.
TEST(Carve, KeptPdlIsTheSocketGapWithATwoVoxelFloorAndTheRootUneroded) {
    const auto& j = syntheticJaw();
    CarveSummary s;
    const CarveOptions o = keptPdlCarveOptions(CarveOptions(), kVoxel);
    const LabelField f = carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s);
    // Tooth 24's socket is 0.25 mm wider than its root: that gap is its PDL.
    const auto& gap = toothSummary(s, 24).thickness;
    ASSERT_GT(gap.samples, 200u);
    EXPECT_NEAR(gap.mean, 0.25, 0.01);
    EXPECT_GE(gap.p05, 0.22);
    EXPECT_LE(gap.p95, 0.28);
    // Tooth 26 fits its socket exactly: the bone gives way to a PDL of two voxels.
    const auto& fit = toothSummary(s, 26).thickness;
    EXPECT_NEAR(fit.mean, kKeptPdlMinVoxels * kVoxel, 0.015);
    // No root erosion: along +y at mid-root of tooth 24, tooth to the input surface, then PDL
    // over the gap, then bone.
    const double r = 1.2;
    const Vec3d axis24(-2.0, 0, -2.5);
    EXPECT_EQ(labelAt(f, axis24 + Vec3d(0, r - kVoxel, 0)), toothLabel(24));
    EXPECT_EQ(labelAt(f, axis24 + Vec3d(0, r + kVoxel, 0)), pdlLabel(24));
    EXPECT_EQ(labelAt(f, axis24 + Vec3d(0, r + 0.25 - kVoxel, 0)), pdlLabel(24));
    EXPECT_EQ(labelAt(f, axis24 + Vec3d(0, r + 0.25 + kVoxel, 0)), boneLabel(Jaw::Mandible));
    const double capsuleMm3 = M_PI * r * r * 8.0 + 4.0 / 3.0 * M_PI * r * r * r;
    EXPECT_NEAR(toothSummary(s, 24).toothVolumeMm3 / capsuleMm3, 1.0, 0.02);
    EXPECT_LT(toothSummary(carvedDefault().summary, 24).toothVolumeMm3, 0.97 * capsuleMm3);  // eroded when generated
}

TEST(Carve, ProfileChangesThicknessAlongTheRoot) {
    const auto& j = syntheticJaw();
    CarveOptions o;
    o.profile = PdlProfile{0.3, 0.2, 0.12};
    CarveSummary s;
    const auto f = carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s);
    // PDL extent along +y from the axis of tooth 26, near the crest and near the apex.
    auto pdlWidth = [&](double z) {
        int n = 0;
        for (double d = 0.5; d < 2.0; d += kVoxel)
            if (labelAt(f, Vec3d(3.4, d, z)) == pdlLabel(26)) ++n;
        return n * kVoxel;
    };
    const double cervical = pdlWidth(-0.6), apical = pdlWidth(-4.6);
    EXPECT_GT(cervical, apical + 0.05) << "cervical " << cervical << " apical " << apical;
    EXPECT_GT(cervical, 0.22);
    EXPECT_LT(apical, 0.19);
    EXPECT_TRUE(std::none_of(s.warnings.begin(), s.warnings.end(),
                             [](const std::string& w) { return w.find("tooth 26") != std::string::npos; }));
}

TEST(Carve, ApexErosionHalvesAndItsPdlKeepsTheThickness) {
    // Down the axis of the exact-fit tooth 26 through its apex (input at z = -6.2), PDL 0.3 mm
    // (e = w = 0.15): the erosion falls to half (0.075 mm) at the apex and the socket side widens
    // to 0.225 mm; with the taper off the apex is eroded by 0.15 mm. Voxel centres every 0.05 mm.
    const auto& j = syntheticJaw();
    const int apexK = -124;  // z = -6.2 = -124 voxels; the axis x = 3.4 is voxel column 68
    const auto at = [&](const LabelField& f, int dk) { return f.labels->tree().getValue(Coord(68, 0, apexK + dk)); };
    CarveOptions o;
    o.pdlThicknessMm = 0.3;
    CarveSummary s;
    const auto f = carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s);
    EXPECT_EQ(at(f, 2), toothLabel(26));  // 0.1 mm inside the input apex
    EXPECT_EQ(at(f, -4), pdlLabel(26));   // 0.2 mm outside
    EXPECT_EQ(at(f, -6), boneLabel(Jaw::Mandible));
    EXPECT_NEAR(toothSummary(s, 26).thickness.mean, 0.3, 0.015);
    o.apexTaperMm = 0;
    const auto off = carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s);
    EXPECT_EQ(at(off, 2), pdlLabel(26));
    EXPECT_EQ(at(off, -4), boneLabel(Jaw::Mandible));
}

TEST(Carve, WideGapMovesTheBoneAtMostTheBoneShift) {
    // Tooth 24 sits in a socket 0.25 mm wider than its root. Default: the bone moves 0.15 mm
    // (0.25 - w), under the 0.2 mm bound. With the bound at 0.05 mm the PDL moves out instead:
    // root not eroded, bone surface 0.05 mm from the input socket, thickness still 0.2 mm; at 0 the
    // bone stays put and the PDL fills the whole 0.25 mm gap.
    const auto& j = syntheticJaw();
    const double r = 1.2;
    const auto at = [&](const LabelField& f, double d) { return labelAt(f, Vec3d(-2.0, d, -2.5)); };
    const auto& def = carvedDefault().field;
    EXPECT_EQ(at(def, r - 0.05), pdlLabel(24));
    EXPECT_EQ(at(def, r + 0.15), boneLabel(Jaw::Mandible));
    CarveOptions o;
    o.boneShiftMaxMm = 0.05;
    CarveSummary s;
    const auto shifted = carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s);
    EXPECT_EQ(at(shifted, r - 0.05), toothLabel(24));
    EXPECT_EQ(at(shifted, r + 0.05), pdlLabel(24));
    EXPECT_EQ(at(shifted, r + 0.15), pdlLabel(24));
    EXPECT_EQ(at(shifted, r + 0.25), boneLabel(Jaw::Mandible));
    EXPECT_NEAR(toothSummary(s, 24).thickness.mean, 0.2, 0.01);
    o.boneShiftMaxMm = 0;
    const auto kept = carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s);
    EXPECT_EQ(at(kept, r + 0.2), pdlLabel(24));
    EXPECT_EQ(at(kept, r + 0.3), boneLabel(Jaw::Mandible));
    EXPECT_NEAR(toothSummary(s, 24).thickness.mean, 0.25, 0.015);
}

TEST(Carve, RootOverlappingTheBoneMovesTheBoneAtMostTheBoneShift) {
    // One tooth (r = 1.2) in a socket narrower than its root, PDL 0.3 mm (e = w = 0.15): the input
    // root overlaps the bone by 0.15 mm, then by 0.25 mm. Without the overlap rule the bone surface
    // would move overlap + w = 0.3 / 0.4 mm. With it the PDL's outer face stops 0.2 mm inside the
    // input bone (at r + 0.05), so the PDL is 0.2 mm thick; at 0.25 mm it stops at its floor
    // (t / 2 = 0.15 mm, outer face on the input root). The root keeps its 0.15 mm erosion.
    const double r = 1.2;
    const Vec3d lo(-3, -3, -9), hi(3, 3, 0);
    const ToothShape tooth{24, 0.0, -5.0, 3.0, r, 0.0};
    std::map<int, openvdb::FloatGrid::ConstPtr> teeth{
        {24, sample([&](const Vec3d& p) { return toothSdf(tooth, p); }, Vec3d(-r, -r, -5 - r), Vec3d(r, r, 3 + r))}};
    CarveOptions o;
    o.pdlThicknessMm = 0.3;
    const auto carve = [&](double overlap, CarveSummary& s) {
        const auto bone = sample([&](const Vec3d& p) { return std::max(boxSdf(p, lo, hi), -(toothSdf(tooth, p) + overlap)); },
                                 lo, hi);
        return carveJaw(Jaw::Mandible, *bone, teeth, o, s);
    };
    // Voxel centres (every 0.05 mm) along +y at mid-root.
    const auto at = [&](const LabelField& f, double d) { return labelAt(f, Vec3d(0.0, d, -2.5)); };
    CarveSummary s;
    const auto f15 = carve(0.15, s);  // input bone surface at r - 0.15
    EXPECT_EQ(at(f15, r - 0.2), toothLabel(24));
    EXPECT_EQ(at(f15, r - 0.1), pdlLabel(24));
    EXPECT_EQ(at(f15, r), pdlLabel(24));
    EXPECT_EQ(at(f15, r + 0.1), boneLabel(Jaw::Mandible));  // 0.25 mm inside the input bone
    EXPECT_NEAR(toothSummary(s, 24).thickness.mean, 0.2, 0.015);
    const auto f25 = carve(0.25, s);  // input bone surface at r - 0.25
    EXPECT_EQ(at(f25, r - 0.2), toothLabel(24));
    EXPECT_EQ(at(f25, r - 0.1), pdlLabel(24));
    EXPECT_EQ(at(f25, r + 0.05), boneLabel(Jaw::Mandible));
    EXPECT_NEAR(toothSummary(s, 24).thickness.mean, 0.15, 0.015);
}

TEST(Carve, RejectsBadOptions) {
    const auto& j = syntheticJaw();
    CarveSummary s;
    CarveOptions o;
    o.pdlRatio = 1.5;
    EXPECT_THROW(carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s), Error);
    o = CarveOptions();
    o.pdlThicknessMm = 0.06;  // under 2 voxels
    EXPECT_THROW(carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s), Error);
    o = CarveOptions();
    o.boneShiftMaxMm = -0.1;
    EXPECT_THROW(carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s), Error);
    o = CarveOptions();
    o.apexTaperMm = std::nan("");
    EXPECT_THROW(carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s), Error);
    o = CarveOptions();
    o.gapFacingDeg = 60;  // would bridge surfaces that turn away from each other
    EXPECT_THROW(carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s), Error);
    o = CarveOptions();
    o.minCapRiseMm = -0.05;
    EXPECT_THROW(carveJaw(Jaw::Mandible, *j.bone, j.teeth, o, s), Error);
    auto other = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0), 0.1f);
    auto teeth = j.teeth;
    teeth[27] = other;
    EXPECT_THROW(carveJaw(Jaw::Mandible, *j.bone, teeth, CarveOptions(), s), Error);
}

TEST(Carve, LabelFieldRoundTripsThroughVdb) {
    const auto& f = carvedDefault().field;
    const auto dir = test::scratchDir("carve-io");
    writeLabelField(f, dir.string());
    const auto back = readLabelField(dir.string());
    EXPECT_EQ(back.jaw, f.jaw);
    EXPECT_DOUBLE_EQ(back.voxelSizeMm, f.voxelSizeMm);
    // tooth 30 floats (no bone contact): its PDL grid has no voxel and is dropped on reading
    ASSERT_EQ(back.distances.size(), f.distances.size() - 1);
    EXPECT_TRUE(f.distances.count(pdlLabel(30)));
    EXPECT_FALSE(back.distances.count(pdlLabel(30)));
    EXPECT_EQ(back.labels->activeVoxelCount(), f.labels->activeVoxelCount());
    ToothCarveSummary a, b;
    measureTooth(f, 26, 0.3, a);
    measureTooth(back, 26, 0.3, b);
    EXPECT_DOUBLE_EQ(a.thickness.mean, b.thickness.mean);
    EXPECT_THROW(readLabelField((dir / "missing").string()), Error);
}

TEST(Carve, EditedFolderWithLabelsAndGridsOutOfStepIsRefusedNamingTheGrid) {
    const auto& f = carvedDefault().field;
    const auto dir = test::scratchDir("carve-io-edit");
    const auto refusal = [&] {
        try {
            readLabelField(dir.string());
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    // a distance grid deleted, its voxels left
    writeLabelField(f, dir.string());
    std::filesystem::remove(dir / "pdl_26.vdb");
    EXPECT_NE(refusal().find("pdl_26.vdb"), std::string::npos) << refusal();
    // tooth 26 and its PDL relabelled, their grids left
    LabelField edited = f;
    edited.labels = f.labels->deepCopy();
    for (auto it = edited.labels->tree().beginValueAll(); it; ++it)
        if (*it == pdlLabel(26) || *it == toothLabel(26)) it.setValue(kOutsideLabel);
    std::filesystem::remove_all(dir);
    writeLabelField(edited, dir.string());
    const std::string why = refusal();
    EXPECT_NE(why.find("tooth_26.vdb"), std::string::npos) << why;
    EXPECT_NE(why.find("no voxel"), std::string::npos) << why;
    // the tooth's grid gone too: accepted; a PDL grid without voxels (as carving writes for a tooth
    // without bone contact) is dropped
    std::filesystem::remove(dir / "tooth_26.vdb");
    EXPECT_EQ(refusal(), "");
    const LabelField back = readLabelField(dir.string());
    EXPECT_FALSE(back.distances.count(toothLabel(26)));
    EXPECT_FALSE(back.distances.count(pdlLabel(26)));
    EXPECT_TRUE(back.distances.count(toothLabel(24)));
}
