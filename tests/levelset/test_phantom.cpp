// The synthetic jaw phantom: closed, oriented surfaces; crowns above the crest, roots in their
// sockets, teeth apart; axes by construction; deterministic; `jawmesh phantom` writes the layout.
#include "io/MeshIO.h"
#include "io/ToothAxes.h"
#include "levelset/Phantom.h"
#include "support/TestData.h"
#include "support/TextFiles.h"

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <numeric>
#include <set>
#include <sstream>
#include <unordered_map>

namespace jawmesh {
namespace {

constexpr double kTestScale = 0.3;  // voxel 0.46 mm: a light phantom for quick tests

// Directed-edge check: a closed, consistently oriented manifold has every directed edge once and
// its reverse once.
struct EdgeReport {
    std::size_t boundary = 0, duplicated = 0;
};
EdgeReport edges(const SurfaceMesh& m) {
    std::unordered_map<std::uint64_t, int> count;
    auto key = [](std::int32_t a, std::int32_t b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b); };
    for (const Tri& t : m.triangles)
        for (int k = 0; k < 3; ++k) ++count[key(t[k], t[(k + 1) % 3])];
    EdgeReport r;
    for (const auto& [e, n] : count) {
        if (n > 1) ++r.duplicated;
        if (!count.count(key(static_cast<std::int32_t>(e & 0xffffffffu), static_cast<std::int32_t>(e >> 32)))) ++r.boundary;
    }
    return r;
}

// Nearest-vertex distances through a uniform hash grid.
class VertexIndex {
public:
    VertexIndex(const std::vector<Vec3>& pts, double cell) : pts_(pts), cell_(cell) {
        for (std::size_t i = 0; i < pts.size(); ++i) cells_[key(pts[i])].push_back(i);
    }
    /// Distance to the nearest vertex if it is within `cell`, else +infinity.
    double nearest(const Vec3& p) const {
        double best = std::numeric_limits<double>::infinity();
        const auto c = coords(p);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    auto it = cells_.find(pack(c[0] + dx, c[1] + dy, c[2] + dz));
                    if (it == cells_.end()) continue;
                    for (std::size_t i : it->second) best = std::min(best, (pts_[i] - p).norm());
                }
        return best <= cell_ ? best : std::numeric_limits<double>::infinity();
    }

private:
    std::array<std::int64_t, 3> coords(const Vec3& p) const {
        return {static_cast<std::int64_t>(std::floor(p.x() / cell_)), static_cast<std::int64_t>(std::floor(p.y() / cell_)),
                static_cast<std::int64_t>(std::floor(p.z() / cell_))};
    }
    static std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) {
        return (static_cast<std::uint64_t>(x & 0x1fffff) << 42) | (static_cast<std::uint64_t>(y & 0x1fffff) << 21) |
               static_cast<std::uint64_t>(z & 0x1fffff);
    }
    std::uint64_t key(const Vec3& p) const {
        const auto c = coords(p);
        return pack(c[0], c[1], c[2]);
    }
    const std::vector<Vec3>& pts_;
    double cell_;
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

// Extent of a tooth along its occlusal axis, relative to the crown centre.
std::pair<double, double> axialRange(const SurfaceMesh& m, const ToothAxes& a) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Vec3& p : m.vertices) {
        const double h = (p - a.crownCentre).dot(a.occlusal);
        lo = std::min(lo, h);
        hi = std::max(hi, h);
    }
    return {lo, hi};
}

// Connected pieces of the tooth surface inside a slab across its long axis (one per root).
int piecesInSlab(const SurfaceMesh& m, const ToothAxes& a, double from, double to) {
    std::vector<int> parent(m.vertices.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
    auto in = [&](std::int32_t v) {
        const double h = (m.vertices[v] - a.crownCentre).dot(a.occlusal);
        return h >= from && h <= to;
    };
    for (const Tri& t : m.triangles)
        for (int k = 0; k < 3; ++k)
            if (in(t[k]) && in(t[(k + 1) % 3])) parent[find(t[k])] = find(t[(k + 1) % 3]);
    std::set<int> roots;
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
        if (in(static_cast<std::int32_t>(v))) roots.insert(find(static_cast<int>(v)));
    return static_cast<int>(roots.size());
}

class PhantomTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        openvdb::initialize();
        for (Jaw jaw : {Jaw::Mandible, Jaw::Maxilla}) {
            PhantomOptions o;
            o.jaw = jaw;
            o.teeth = 16;
            o.trianglesScale = kTestScale;
            const auto t0 = std::chrono::steady_clock::now();
            jaws().push_back(makePhantom(o));
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::size_t teethTris = 0;
            for (const auto& [unn, m] : jaws().back().teeth) teethTris += m.triangles.size();
            std::printf("[phantom] %s scale %.2f: %.2f s, bone %zu triangles, 16 teeth %zu triangles\n",
                        jawName(jaw).c_str(), kTestScale, s, jaws().back().bone.triangles.size(), teethTris);
        }
    }
    static std::vector<PhantomJaw>& jaws() {
        static std::vector<PhantomJaw> j;
        return j;
    }
};

TEST_F(PhantomTest, SurfacesAreClosedOrientedWithPositiveVolume) {
    for (const PhantomJaw& jaw : jaws()) {
        ASSERT_EQ(jaw.teeth.size(), 16u);
        std::vector<const SurfaceMesh*> all{&jaw.bone};
        for (const auto& [unn, m] : jaw.teeth) all.push_back(&m);
        for (const SurfaceMesh* m : all) {
            const EdgeReport r = edges(*m);
            EXPECT_EQ(r.boundary, 0u);
            EXPECT_EQ(r.duplicated, 0u);
            EXPECT_GT(signedVolume(*m), 0.0);
        }
        for (const auto& [unn, m] : jaw.teeth) {
            EXPECT_EQ(jawOfTooth(unn), jaw.jaw);
            const double v = signedVolume(m);
            EXPECT_GT(v, 150.0) << "tooth " << unn;   // incisors ~250 mm^3, molars ~900 mm^3
            EXPECT_LT(v, 2000.0) << "tooth " << unn;
        }
    }
}

TEST_F(PhantomTest, CrownsStandAboveTheBoneAndRootsTouchIt) {
    double worstContact = 1.0;
    for (const PhantomJaw& jaw : jaws()) {
        const VertexIndex bone(jaw.bone.vertices, jaw.voxelSizeMm);
        for (const auto& [unn, m] : jaw.teeth) {
            const ToothAxes& a = jaw.axes.at(unn);
            const auto [lo, hi] = axialRange(m, a);
            // Bone near the tooth: within 6 mm of its long axis.
            double boneTop = -std::numeric_limits<double>::infinity();
            for (const Vec3& p : jaw.bone.vertices) {
                const Vec3 d = p - a.crownCentre;
                const double h = d.dot(a.occlusal);
                if ((d - h * a.occlusal).norm() < 6.0) boneTop = std::max(boneTop, h);
            }
            EXPECT_GT(hi - boneTop, 2.0) << "tooth " << unn;
            EXPECT_GT(boneTop, lo + 5.0) << "tooth " << unn << ": no bone around the root";
            // Apical 40 % of the tooth: root surface, shared with the socket.
            std::size_t roots = 0, touching = 0;
            for (const Vec3& p : m.vertices) {
                if ((p - a.crownCentre).dot(a.occlusal) > lo + 0.4 * (hi - lo)) continue;
                ++roots;
                if (bone.nearest(p) <= jaw.voxelSizeMm) ++touching;
            }
            ASSERT_GT(roots, 50u);
            EXPECT_GE(static_cast<double>(touching) / roots, 0.95) << "tooth " << unn;
            worstContact = std::min(worstContact, static_cast<double>(touching) / roots);
        }
    }
    std::printf("[phantom] worst share of root vertices within a voxel of the bone: %.3f\n", worstContact);
}

double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 d = b - a;
    const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (p - a - t * d).norm();
}
double triangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = (b - a).cross(c - a);
    if (n.squaredNorm() > 0) {
        const Vec3 q = p - n * ((p - a).dot(n) / n.squaredNorm());
        if ((b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 && (a - c).cross(q - c).dot(n) >= 0)
            return (p - q).norm();
    }
    return std::min({segmentDistance(p, a, b), segmentDistance(p, b, c), segmentDistance(p, c, a)});
}

// Smallest distance from B's vertices to A's triangles, by brute force over where the two
// (0.5 mm-padded) boxes overlap; +infinity when they do not.
double closestApproach(const SurfaceMesh& a, const SurfaceMesh& b) {
    BBox box;
    const BBox ba = boundingBox(a), bb = boundingBox(b);
    box.min = ba.min.cwiseMax(bb.min) - Vec3::Constant(0.5);
    box.max = ba.max.cwiseMin(bb.max) + Vec3::Constant(0.5);
    auto inside = [&](const Vec3& p) { return (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all(); };
    std::vector<Tri> near;
    for (const Tri& t : a.triangles)
        if (inside(a.vertices[t[0]]) || inside(a.vertices[t[1]]) || inside(a.vertices[t[2]])) near.push_back(t);
    double closest = std::numeric_limits<double>::infinity();
    for (const Vec3& p : b.vertices)
        if (inside(p))
            for (const Tri& t : near) closest = std::min(closest, triangleDistance(p, a.vertices[t[0]], a.vertices[t[1]], a.vertices[t[2]]));
    return closest;
}

TEST_F(PhantomTest, AdjacentTeethAreAtLeast0_3mmApart) {
    for (const PhantomJaw& jaw : jaws()) {
        double smallest = std::numeric_limits<double>::infinity();
        for (auto it = jaw.teeth.begin(); std::next(it) != jaw.teeth.end(); ++it) {
            const auto& [unnA, a] = *it;
            const auto& [unnB, b] = *std::next(it);
            // Both ways: vertices of each against the other's triangles.
            const double gap = std::min(closestApproach(a, b), closestApproach(b, a));
            EXPECT_GE(gap, 0.3) << "teeth " << unnA << " and " << unnB;
            smallest = std::min(smallest, gap);
            // Consecutive UNNs are neighbours on the arch (the test is not vacuous).
            EXPECT_LT((jaw.axes.at(unnA).crownCentre - jaw.axes.at(unnB).crownCentre).norm(), 13.0);
        }
        std::printf("[phantom] %s: smallest gap between adjacent teeth %.2f mm\n", jawName(jaw.jaw).c_str(), smallest);
    }
}

TEST_F(PhantomTest, AxesAreOrthonormalAndPointToCrownLabialAndDistal) {
    for (const PhantomJaw& jaw : jaws()) {
        const int c1 = jaw.jaw == Jaw::Mandible ? 24 : 8, c2 = jaw.jaw == Jaw::Mandible ? 25 : 9;
        const Vec3 front = 0.5 * (jaw.axes.at(c1).crownCentre + jaw.axes.at(c2).crownCentre);
        Vec3 centroid = Vec3::Zero();
        for (const auto& [unn, a] : jaw.axes) centroid += a.crownCentre / static_cast<double>(jaw.axes.size());
        for (const auto& [unn, a] : jaw.axes) {
            EXPECT_NEAR(a.mesialDistal.norm(), 1.0, 1e-9);
            EXPECT_NEAR(a.labial.norm(), 1.0, 1e-9);
            EXPECT_NEAR(a.occlusal.norm(), 1.0, 1e-9);
            EXPECT_NEAR(a.mesialDistal.dot(a.labial), 0.0, 1e-9);
            EXPECT_NEAR(a.mesialDistal.dot(a.occlusal), 0.0, 1e-9);
            EXPECT_NEAR(a.labial.dot(a.occlusal), 0.0, 1e-9);
            const auto [lo, hi] = axialRange(jaw.teeth.at(unn), a);
            EXPECT_GT(hi, 2.5) << unn;     // crown on the +z side of its centre
            EXPECT_LT(lo, -12.0) << unn;   // root on the other
            EXPECT_GT(a.occlusal.z() * (jaw.jaw == Jaw::Mandible ? 1 : -1), 0.8) << unn;
            Vec3 out = a.crownCentre - centroid;
            out.z() = 0;
            EXPECT_GT(a.labial.dot(out), 0.0) << unn;
            EXPECT_GT((a.crownCentre + a.mesialDistal - front).norm(), (a.crownCentre - front).norm()) << unn;
        }
    }
}

TEST_F(PhantomTest, RootCountsFollowToothKind) {
    for (const PhantomJaw& jaw : jaws()) {
        for (const auto& [unn, m] : jaw.teeth) {
            const int fromMidline = jaw.jaw == Jaw::Mandible ? (unn <= 24 ? 25 - unn : unn - 24) : (unn <= 8 ? 9 - unn : unn - 8);
            const int expected = fromMidline <= 5 ? 1 : (jaw.jaw == Jaw::Mandible ? 2 : 3);
            const ToothAxes& a = jaw.axes.at(unn);
            const auto [lo, hi] = axialRange(m, a);
            const double at = lo + 0.25 * (hi - lo);
            EXPECT_EQ(piecesInSlab(m, a, at, at + 1.2), expected) << "tooth " << unn;
        }
    }
}

TEST_F(PhantomTest, JawsFaceEachOtherWithAGap) {
    double lowerTop = -1e9, upperBottom = 1e9;
    for (const auto& [unn, m] : jaws()[0].teeth)
        for (const Vec3& p : m.vertices) lowerTop = std::max(lowerTop, p.z());
    for (const auto& [unn, m] : jaws()[1].teeth)
        for (const Vec3& p : m.vertices) upperBottom = std::min(upperBottom, p.z());
    EXPECT_GT(upperBottom - lowerTop, 0.5);
    EXPECT_LT(upperBottom - lowerTop, 5.0);
    // Arch like a real mandible: ~50 mm wide at the first molars, ~45 mm deep (central incisors to
    // second molars).
    const auto& lower = jaws()[0].axes;
    const double molarWidth = (lower.at(19).crownCentre - lower.at(30).crownCentre).norm();
    EXPECT_GT(molarWidth, 40.0);
    EXPECT_LT(molarWidth, 55.0);
    const double depth = 0.5 * (lower.at(18).crownCentre + lower.at(31).crownCentre).y() -
                         0.5 * (lower.at(24).crownCentre + lower.at(25).crownCentre).y();
    EXPECT_GT(depth, 30.0);
    EXPECT_LT(depth, 50.0);
    const BBox arch = boundingBox(jaws()[0].bone);
    EXPECT_GT(arch.size().x(), 50.0);
    EXPECT_LT(arch.size().x(), 80.0);
}

TEST(Phantom, KeepsTheTeethNearestTheMidline) {
    auto unns = [](Jaw jaw, int n) {
        PhantomOptions o;
        o.jaw = jaw;
        o.teeth = n;
        o.trianglesScale = 0.1;
        std::set<int> s;
        for (const auto& [unn, m] : makePhantom(o).teeth) s.insert(unn);
        return s;
    };
    EXPECT_EQ(unns(Jaw::Mandible, 1), std::set<int>({24}));
    EXPECT_EQ(unns(Jaw::Mandible, 3), std::set<int>({23, 24, 25}));
    EXPECT_EQ(unns(Jaw::Maxilla, 2), std::set<int>({8, 9}));
    PhantomOptions bad;
    bad.teeth = 0;
    EXPECT_THROW(makePhantom(bad), Error);
    bad.teeth = 17;
    EXPECT_THROW(makePhantom(bad), Error);
    bad.teeth = 2;
    bad.trianglesScale = 0;
    EXPECT_THROW(makePhantom(bad), Error);
}

TEST(Phantom, SameSeedSameFilesOtherSeedOtherFiles) {
    auto write = [](std::uint32_t seed, const std::string& name) {
        PhantomOptions o;
        o.teeth = 4;
        o.seed = seed;
        o.trianglesScale = 0.15;
        const auto dir = test::scratchDir(name);
        writePhantomCase({makePhantom(o)}, dir.string());
        return dir / "input" / "mandible";
    };
    const auto a = write(7, "phantom-seed-a"), b = write(7, "phantom-seed-b"), c = write(8, "phantom-seed-c");
    for (const std::string f : {"bone/mandible.stl", "teeth/tooth_24.stl", "teeth/tooth_23.stl", "teeth_axes_mandible.json"}) {
        ASSERT_TRUE(std::filesystem::exists(a / f)) << f;
        EXPECT_EQ(test::readText(a / f), test::readText(b / f)) << f;
        EXPECT_NE(test::readText(a / f), test::readText(c / f)) << f;
    }
}

TEST(Phantom, RefusesToMixWithAnotherCase) {
    PhantomOptions o;
    o.teeth = 2;
    o.trianglesScale = 0.1;
    const auto dir = test::scratchDir("phantom-mix");
    std::filesystem::create_directories(dir / "input" / "mandible" / "teeth");
    std::ofstream(dir / "input" / "mandible" / "teeth" / "tooth_18.stl") << "solid x\nendsolid x\n";
    EXPECT_THROW(writePhantomCase({makePhantom(o)}, dir.string()), Error);
}

TEST(Phantom, CommandWritesTheCaseLayout) {
    const auto dir = test::scratchDir("phantom-cli");
    const std::string cmd = std::string(JAWMESH_BINARY) + " -q phantom " + dir.string() +
                            " --teeth 3 --seed 5 --jaw both --triangles-scale 0.1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    for (const std::string jaw : {"mandible", "maxilla"}) {
        const auto root = dir / "input" / jaw;
        const SurfaceMesh bone = readSurface((root / "bone" / (jaw + ".stl")).string());
        EXPECT_GT(bone.triangles.size(), 1000u);
        const auto axes = readToothAxes((root / ("teeth_axes_" + jaw + ".json")).string());
        EXPECT_EQ(axes.size(), 3u);
        for (const auto& [unn, a] : axes) {
            const SurfaceMesh tooth = readSurface((root / "teeth" / ("tooth_" + std::to_string(unn) + ".stl")).string());
            EXPECT_EQ(edges(tooth).boundary, 0u);
            EXPECT_GT(signedVolume(tooth), 0.0);
        }
    }
    const std::string bad = std::string(JAWMESH_BINARY) + " -q phantom " + dir.string() + " --teeth 20 2>/dev/null";
    EXPECT_NE(std::system(bad.c_str()), 0);
}

}  // namespace
}  // namespace jawmesh
