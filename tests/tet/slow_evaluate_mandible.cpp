// Evaluation on the shared OpenMandible data (label slow).
// 1. The distance machinery on real surfaces: nearest distances on the 1.7 M-triangle bone against
//    brute force over every bone triangle that could be nearest (a provable superset: those meeting
//    the tooth's box grown by a bound on the distance); means, percentiles and maxima of a real
//    tooth against a copy moved by 0.1 mm against brute force on random area samples.
// 2. The report of a full mandible run when one exists (JAWMESH_MANDIBLE_RUN=<out>/mandible): its
//    tooth distances and PDL thicknesses against brute force on random area samples. A full run of
//    the mandible takes far longer than a test may (carving ~7 min, interface surface ~20 min and
//    TetGen on 1.2 M triangles on 2 cores), so the test does not make one; it skips without it.
#include "support/BruteForceDistance.h"
#include "filters/SurfaceDistance.h"
#include "io/Case.h"
#include "io/GmshReader.h"
#include "support/TestData.h"
#include "tet/EvaluateMesh.h"
#include "tet/RegionSurfaces.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

using namespace jawmesh;
using namespace jawmesh::test;

namespace {


std::vector<Triangle> triangles(const SurfaceMesh& s) {
    std::vector<Triangle> out;
    for (const Tri& t : s.triangles)
        out.push_back({s.vertices[static_cast<std::size_t>(t[0])], s.vertices[static_cast<std::size_t>(t[1])], s.vertices[static_cast<std::size_t>(t[2])]});
    return out;
}

/// Triangles meeting the box [lo - r, hi + r]: every triangle within r of a point of the box.
std::vector<Triangle> near(const std::vector<Triangle>& ts, const Vec3& lo, const Vec3& hi, double r) {
    std::vector<Triangle> out;
    for (const Triangle& t : ts) {
        const Vec3 tlo = t[0].cwiseMin(t[1]).cwiseMin(t[2]), thi = t[0].cwiseMax(t[1]).cwiseMax(t[2]);
        if (((tlo.array() <= hi.array() + r) && (thi.array() >= lo.array() - r)).all()) out.push_back(t);
    }
    return out;
}

/// Points uniform by area, stratified: the i-th falls in the i-th of `count` equal slices of the
/// cumulative area (in triangle order, which follows the surface), so the mean of a smooth field
/// converges much faster than with independent draws (real tooth-to-bone distances spread over
/// 0-9 mm: 1,500 independent draws leave a 2-3% error).
std::vector<Vec3> areaSamples(const std::vector<Triangle>& ts, int count, unsigned seed) {
    std::vector<double> cumulative;
    double total = 0;
    for (const Triangle& t : ts) cumulative.push_back(total += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Vec3> out;
    for (int i = 0; i < count; ++i) {
        const double at = (i + u(rng)) / count * total;
        const std::size_t k = std::min(ts.size() - 1, static_cast<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin()));
        const double r1 = std::sqrt(u(rng)), r2 = u(rng);
        out.push_back((1 - r1) * ts[k][0] + r1 * (1 - r2) * ts[k][1] + r1 * r2 * ts[k][2]);
    }
    return out;
}

double bruteDistance(const Vec3& p, const std::vector<Triangle>& ts) {
    double d = INFINITY;
    for (const Triangle& t : ts) d = std::min(d, distanceToTriangle(p, t));
    return d;
}

void expectMatch(double report, double independent, const std::string& what) {
    EXPECT_NEAR(report, independent, std::max(0.01 * std::abs(independent), 0.005)) << what;
}

}  // namespace

TEST(SlowEval, RealSurfaceDistancesMatchBruteForce) {
    const std::string caseDir = sharedData("openmandible");
    JAWMESH_REQUIRE_SHARED(caseDir);
    const JawSurfaces jaw = loadJaw(discoverCase(caseDir).jaws.front());
    ASSERT_GT(jaw.bone.triangles.size(), 1000000u);
    const auto start = std::chrono::steady_clock::now();
    const TriangleBvh bone = buildTriangleBvh(jaw.bone);
    std::cout << "BVH over " << jaw.bone.triangles.size() << " triangles: "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
    const std::vector<Triangle> boneTriangles = triangles(jaw.bone);
    int checked = 0;
    for (const auto& [unn, tooth] : jaw.teeth) {
        if (checked++ == 2) break;  // two teeth keep the brute force within a minute or two
        const std::vector<Triangle> toothTriangles = triangles(tooth);
        // (a) Nearest distances on the real 1.7 M-triangle bone equal brute force exactly, over
        // every bone triangle meeting the tooth's box grown by the largest distance found.
        const std::vector<Vec3> points = areaSamples(toothTriangles, 100, static_cast<unsigned>(unn));
        double farthest = 0;
        for (const Vec3& p : points) farthest = std::max(farthest, std::sqrt(closestTriangle(bone, p).squaredDistanceMm2));
        const BBox box = boundingBox(tooth);
        const std::vector<Triangle> candidates = near(boneTriangles, box.min, box.max, farthest + 0.5);
        for (const Vec3& p : points)
            EXPECT_NEAR(std::sqrt(closestTriangle(bone, p).squaredDistanceMm2), bruteDistance(p, candidates), 1e-12) << "tooth " << unn;

        // (b) Report-style summaries at the scale of a mesh's deviation: the real tooth against
        // itself moved by 0.1 mm (distances 0..0.1 mm, with the real triangulation's detail).
        SurfaceMesh moved = tooth;
        for (Vec3& v : moved.vertices) v += Vec3(0.08, -0.06, 0.0);
        const TriangleBvh movedBvh = buildTriangleBvh(moved);
        const DistanceSamples samples = sampleDistances(tooth, movedBvh, 0.2);
        const DistanceSummary s =
            summarizeDistances(tooth, samples, std::vector<int>(tooth.triangles.size(), 0), 1, movedBvh, 0.002).front();
        const std::vector<Triangle> movedTriangles = triangles(moved);
        std::vector<double> d;
        for (const Vec3& p : areaSamples(toothTriangles, 1500, static_cast<unsigned>(unn) + 100)) d.push_back(bruteDistance(p, movedTriangles));
        std::sort(d.begin(), d.end());
        double mean = 0;
        for (double x : d) mean += x / static_cast<double>(d.size());
        const std::string what = "tooth " + std::to_string(unn) + " vs moved copy";
        expectMatch(s.distance.mean, mean, what + " mean");
        expectMatch(s.distance.median, d[d.size() / 2], what + " median");
        expectMatch(s.distance.p95, d[static_cast<std::size_t>(0.95 * static_cast<double>(d.size()))], what + " p95");
        EXPECT_GE(s.distance.max, d.back() - 1e-9) << what;
        EXPECT_LE(s.distance.max, 0.1 + 1e-9) << what;  // no point moves farther than the shift
        EXPECT_NEAR(bruteDistance(s.maxAt, movedTriangles), s.distance.max, 1e-9) << what;  // attained there
        std::cout << what << ": mean " << s.distance.mean << " (brute " << mean << "), max " << s.distance.max << " (sampled "
                  << d.back() << ")\n";
    }
}

TEST(SlowEval, MandibleRunReportMatchesBruteForce) {
    const std::string caseDir = sharedData("openmandible");
    JAWMESH_REQUIRE_SHARED(caseDir);
    const char* run = std::getenv("JAWMESH_MANDIBLE_RUN");
    if (!run || !std::filesystem::exists(std::string(run) + "/volumetric_meshes/mandible.msh"))
        GTEST_SKIP() << "no mandible run output: set JAWMESH_MANDIBLE_RUN=<out>/mandible after `jawmesh run " << caseDir
                     << " -o <out>` (too long to make inside a test)";
    const TetMesh mesh = readGmsh(std::string(run) + "/volumetric_meshes/mandible.msh");
    const JawSurfaces input = loadJaw(discoverCase(caseDir).jaws.front());
    const auto start = std::chrono::steady_clock::now();
    const nlohmann::json report = evaluateMesh(mesh, &input);
    std::cout << "evaluateMesh: " << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s, "
              << report["verdict"]["line"].get<std::string>() << "\n";
    ASSERT_TRUE(report["validation"]["valid"].get<bool>());
    const auto boundaries = regionBoundaries(mesh);
    int checked = 0;
    for (const auto& dom : report["distance"]["domains"]) {
        if (dom["kind"] != "tooth" || checked++ == 3) continue;
        const Label label = dom["label"].get<Label>();
        const RegionBoundary& b = boundaries.at(label);
        std::vector<Triangle> crown;
        const auto all = triangles(b.surface);
        for (std::size_t t = 0; t < all.size(); ++t)
            if (b.otherSide[t] == kOutsideLabel) crown.push_back(all[t]);
        const std::vector<Triangle> in = triangles(input.teeth.at(labelUnn(label)));
        double mean = 0;
        const auto pts = areaSamples(crown, 1000, 5);
        for (const Vec3& p : pts) mean += bruteDistance(p, in) / static_cast<double>(pts.size());
        // The faces against the outside are the crown and its cervical band: their area-weighted mean.
        const auto& crownPart = dom["parts"]["crown"]["output_to_input"];
        const auto& bandPart = dom["parts"]["cervical"]["output_to_input"];
        const double crownArea = crownPart["area_mm2"].get<double>(), bandArea = bandPart["area_mm2"].get<double>();
        const double reported =
            (crownPart["mean"].get<double>() * crownArea + bandPart["mean"].get<double>() * bandArea) / (crownArea + bandArea);
        expectMatch(reported, mean, dom["name"].get<std::string>() + " crown and band mean");
    }
    for (const auto& row : report["pdl_thickness"]["teeth"]) {
        const int unn = row["tooth"].get<int>();
        const RegionBoundary& b = boundaries.at(pdlLabel(unn));
        std::vector<Triangle> toothSide, boneSide;
        const auto all = triangles(b.surface);
        for (std::size_t t = 0; t < all.size(); ++t) {
            if (b.otherSide[t] == toothLabel(unn)) toothSide.push_back(all[t]);
            if (b.otherSide[t] == kMandibleBoneLabel) boneSide.push_back(all[t]);
        }
        std::vector<double> d;
        for (const Vec3& p : areaSamples(toothSide, 2000, static_cast<unsigned>(unn))) d.push_back(bruteDistance(p, boneSide));
        std::sort(d.begin(), d.end());
        double mean = 0;
        for (double x : d) mean += x / static_cast<double>(d.size());
        expectMatch(row["mean"].get<double>(), mean, "pdl " + std::to_string(unn) + " mean");
        expectMatch(row["median"].get<double>(), d[d.size() / 2], "pdl " + std::to_string(unn) + " median");
    }
    // Issue #26: every crown keeps its input shape within 0.05 mm above the cervical band (0.027
    // measured), and the report's verdict passes.
    int crowns = 0;
    for (const auto& dom : report["distance"]["domains"]) {
        if (dom["kind"] != "tooth") continue;
        ++crowns;
        EXPECT_LE(dom["parts"]["crown"]["hausdorff_mm"].get<double>(), 0.05) << dom["name"];
        EXPECT_GT(dom["parts"]["crown"]["output_to_input"]["area_mm2"].get<double>(),
                  5 * dom["parts"]["cervical"]["output_to_input"]["area_mm2"].get<double>())
            << dom["name"] << ": the band is most of the crown";
    }
    EXPECT_EQ(crowns, 14);
    EXPECT_EQ(report["verdict"]["status"], "pass") << report["verdict"]["line"];
}
