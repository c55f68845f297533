// evaluateMesh() against an independent computation on the synthetic jaw: boundary faces found by
// a face map of our own, distances by brute force over every triangle with a point-triangle
// distance written here, random area samples for means and percentiles; plus the values known
// by construction (tests/support/SyntheticJaw.h). Report numbers must match within 1% or 0.005 mm.
#include "support/BruteForceDistance.h"
#include "support/SyntheticJaw.h"
#include "tet/EvaluateMesh.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>

using namespace jawmesh;
using namespace jawmesh::test;

namespace {


struct Nearest {
    double distance;
    std::size_t index;
};
Nearest bruteNearest(const Vec3& p, const std::vector<Triangle>& to) {
    Nearest n{INFINITY, 0};
    for (std::size_t i = 0; i < to.size(); ++i) {
        const double d = distanceToTriangle(p, to[i]);
        if (d < n.distance) n = {d, i};
    }
    return n;
}

std::vector<Triangle> triangles(const SurfaceMesh& s) {
    std::vector<Triangle> out;
    for (const Tri& t : s.triangles)
        out.push_back({s.vertices[static_cast<std::size_t>(t[0])], s.vertices[static_cast<std::size_t>(t[1])],
                       s.vertices[static_cast<std::size_t>(t[2])]});
    return out;
}

/// Faces of `label`'s tets whose other side is not `label`, with the label across (0 outside).
std::vector<std::pair<Triangle, Label>> boundaryFaces(const TetMesh& m, Label label) {
    std::map<std::array<std::int32_t, 3>, std::vector<std::size_t>> faces;
    for (std::size_t t = 0; t < m.tets.size(); ++t)
        for (int skip = 0; skip < 4; ++skip) {
            std::array<std::int32_t, 3> key;
            int k = 0;
            for (int i = 0; i < 4; ++i)
                if (i != skip) key[static_cast<std::size_t>(k++)] = m.tets[t][static_cast<std::size_t>(i)];
            std::sort(key.begin(), key.end());
            faces[key].push_back(t);
        }
    std::vector<std::pair<Triangle, Label>> out;
    for (const auto& [key, tets] : faces) {
        bool mine = false, same = false;
        Label other = kOutsideLabel;
        for (std::size_t t : tets) {
            if (m.labels[t] == label) (mine ? same : mine) = true;
            else other = m.labels[t];
        }
        if (!mine || same) continue;
        out.push_back({{m.nodes[static_cast<std::size_t>(key[0])], m.nodes[static_cast<std::size_t>(key[1])],
                        m.nodes[static_cast<std::size_t>(key[2])]},
                       other});
    }
    return out;
}

/// Uniform random points on the triangles (by area), with the index of the triangle each lies on.
std::vector<std::pair<Vec3, std::size_t>> areaSamples(const std::vector<Triangle>& ts, int count, unsigned seed) {
    std::vector<double> cumulative;
    double total = 0;
    for (const Triangle& t : ts) cumulative.push_back(total += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<std::pair<Vec3, std::size_t>> out;
    for (int i = 0; i < count; ++i) {
        const std::size_t k = static_cast<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), u(rng) * total) - cumulative.begin());
        const Triangle& t = ts[std::min(k, ts.size() - 1)];
        double r1 = std::sqrt(u(rng)), r2 = u(rng);
        out.push_back({(1 - r1) * t[0] + r1 * (1 - r2) * t[1] + r1 * r2 * t[2], std::min(k, ts.size() - 1)});
    }
    return out;
}

struct Stats {
    double mean = 0, max = 0, min = INFINITY, p05 = 0, median = 0, p95 = 0;
};
Stats stats(std::vector<double> v) {
    Stats s;
    if (v.empty()) return s;
    for (double x : v) {
        s.mean += x / static_cast<double>(v.size());
        s.max = std::max(s.max, x);
        s.min = std::min(s.min, x);
    }
    std::sort(v.begin(), v.end());
    const auto q = [&](double f) { return v[std::min(v.size() - 1, static_cast<std::size_t>(f * static_cast<double>(v.size())))]; };
    s.p05 = q(0.05);
    s.median = q(0.5);
    s.p95 = q(0.95);
    return s;
}

void expectMatch(double report, double independent, const std::string& what) {
    EXPECT_NEAR(report, independent, std::max(0.01 * std::abs(independent), 0.005)) << what;
}

bool isRoot(Label other) { return other != kOutsideLabel && labelKind(other) != LabelKind::Tooth; }

class EvaluateSyntheticJaw : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        mesh_ = new TetMesh(syntheticJawMesh());
        input_ = new JawSurfaces(syntheticJawInput());
        EvalOptions o;
        o.cervicalBandMm = 0;  // crown and root split by the crest alone; the band has its own test
        report_ = new nlohmann::json(evaluateMesh(*mesh_, input_, o));
    }
    static void TearDownTestSuite() {
        delete mesh_;
        delete input_;
        delete report_;
    }
    static const nlohmann::json& domain(const std::string& name) {
        for (const auto& d : (*report_)["distance"]["domains"])
            if (d["name"] == name) return d;
        throw std::runtime_error("no domain " + name);
    }
    static TetMesh* mesh_;
    static JawSurfaces* input_;
    static nlohmann::json* report_;
};
TetMesh* EvaluateSyntheticJaw::mesh_ = nullptr;
JawSurfaces* EvaluateSyntheticJaw::input_ = nullptr;
nlohmann::json* EvaluateSyntheticJaw::report_ = nullptr;

}  // namespace

TEST_F(EvaluateSyntheticJaw, CountsAndVerdict) {
    const auto& r = *report_;
    EXPECT_TRUE(r["validation"]["valid"].get<bool>()) << r["validation"].dump(1);
    std::map<Label, std::size_t> tets;
    for (Label l : mesh_->labels) ++tets[l];
    ASSERT_EQ(r["regions"].size(), tets.size());
    for (const auto& region : r["regions"]) EXPECT_EQ(region["tets"].get<std::size_t>(), tets[region["label"].get<Label>()]);
    EXPECT_EQ(r["sizes"]["tooth"]["input_triangles"].get<std::size_t>(),
              input_->teeth.at(24).triangles.size() + input_->teeth.at(25).triangles.size());
    // Grid tets are all congruent: every quality measure has a single value, the path tet's.
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(1, 1, 1);
    const double volume = 1.0 / 6, R = std::sqrt(3.0) / 2;
    const double area = 0.5 * ((b - a).cross(c - a).norm() + (b - a).cross(d - a).norm() + (c - a).cross(d - a).norm() +
                               (c - b).cross(d - b).norm());
    const auto& overall = r["quality"]["overall"];
    EXPECT_NEAR(overall["radius_ratio"]["min"].get<double>(), 3 * (3 * volume / area) / R, 1e-9);
    EXPECT_NEAR(overall["radius_ratio"]["max"].get<double>(), 3 * (3 * volume / area) / R, 1e-9);
    EXPECT_NEAR(overall["radius_edge_ratio"]["max"].get<double>(), R / 1.0, 1e-9);
    // Crowns are 0.05 mm inside the input, the PDL of tooth 24 is 0.4 mm on one side: warnings.
    EXPECT_EQ(r["verdict"]["status"], "warn") << r["verdict"]["line"];
    EXPECT_NE(r["verdict"]["line"].get<std::string>().find("PDL thickness"), std::string::npos);
}

TEST_F(EvaluateSyntheticJaw, ToothDistancesMatchBruteForceAndConstruction) {
    for (int unn : {24, 25}) {
        const auto faces = boundaryFaces(*mesh_, toothLabel(unn));
        const std::vector<Triangle> input = triangles(input_->teeth.at(unn));
        std::vector<Triangle> output;
        for (const auto& f : faces) output.push_back(f.first);
        const auto& parts = domain("tooth_" + std::to_string(unn))["parts"];
        // input -> output: each input point goes to the part of its nearest output face
        std::vector<double> inOutOf[2];
        for (const auto& [p, tri] : areaSamples(input, 4000, 11)) {
            const Nearest n = bruteNearest(p, output);
            inOutOf[isRoot(faces[n.index].second)].push_back(n.distance);
        }
        for (const bool root : {false, true}) {
            const std::string part = root ? "root" : "crown";
            std::vector<Triangle> mine;
            for (const auto& f : faces)
                if (isRoot(f.second) == root) mine.push_back(f.first);
            std::vector<double> outIn;  // output -> input on this part
            for (const auto& [p, tri] : areaSamples(mine, 1500, 7)) outIn.push_back(bruteNearest(p, input).distance);
            const std::vector<double>& inOut = inOutOf[root];
            const Stats a = stats(outIn), b = stats(inOut);
            const auto& rep = parts[part];
            const std::string what = "tooth " + std::to_string(unn) + " " + part;
            expectMatch(rep["output_to_input"]["mean"].get<double>(), a.mean, what + " out->in mean");
            expectMatch(rep["input_to_output"]["mean"].get<double>(), b.mean, what + " in->out mean");
            expectMatch(rep["output_to_input"]["p95"].get<double>(), a.p95, what + " out->in p95");
            // Random samples only bound a maximum from below; the construction gives it exactly.
            EXPECT_GE(rep["output_to_input"]["max"].get<double>(), a.max - 1e-9) << what;
            EXPECT_GE(rep["input_to_output"]["max"].get<double>(), b.max - 1e-9) << what;
            const double outInMax = root ? 0.1 : 0.05;
            const double inOutMax = root ? std::sqrt(0.05 * 0.05 * 2 + 0.1 * 0.1) : 0.05 * std::sqrt(3.0);
            EXPECT_NEAR(rep["output_to_input"]["max"].get<double>(), outInMax, 0.002) << what;
            EXPECT_NEAR(rep["input_to_output"]["max"].get<double>(), inOutMax, 0.002) << what;
            EXPECT_NEAR(rep["hausdorff_mm"].get<double>(), std::max(outInMax, inOutMax), 0.002) << what;
        }
        EXPECT_NEAR(parts["crown"]["output_to_input"]["mean"].get<double>(), 0.05, 1e-9);  // every crown point is 0.05 in
    }
    const auto& crowns = (*report_)["distance"]["summary"]["crowns"];
    EXPECT_EQ(crowns["domains"].get<int>(), 2);
    EXPECT_NEAR(crowns["hausdorff_mm"].get<double>(), 0.05 * std::sqrt(3.0), 0.002);
}

// The cervical band: crown faces with a corner within the band of a root face are a part of their
// own, so the crown's figures are those of the faces above it (brute force over the root faces).
TEST_F(EvaluateSyntheticJaw, CervicalBandIsTheCrownNearTheRoot) {
    EvalOptions o;
    o.cervicalBandMm = 0.75;
    const nlohmann::json r = evaluateMesh(*mesh_, input_, o);
    for (int unn : {24, 25}) {
        const auto faces = boundaryFaces(*mesh_, toothLabel(unn));
        std::vector<Triangle> root;
        for (const auto& f : faces)
            if (isRoot(f.second)) root.push_back(f.first);
        double areaOf[3] = {0, 0, 0};  // crown, root, band
        for (const auto& [tri, other] : faces) {
            int part = isRoot(other) ? 1 : 0;
            if (part == 0)
                for (const Vec3& corner : tri)
                    if (bruteNearest(corner, root).distance <= o.cervicalBandMm) part = 2;
            areaOf[part] += 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]).norm();
        }
        ASSERT_GT(areaOf[0], 0.0);
        ASSERT_GT(areaOf[2], 0.0);
        nlohmann::json parts;
        for (const auto& d : r["distance"]["domains"])
            if (d["name"] == "tooth_" + std::to_string(unn)) parts = d["parts"];
        ASSERT_FALSE(parts.is_null());
        const char* names[3] = {"crown", "root", "cervical"};
        for (int g = 0; g < 3; ++g)
            EXPECT_NEAR(parts[names[g]]["output_to_input"]["area_mm2"].get<double>(), areaOf[g], 1e-9 * (1 + areaOf[g]))
                << "tooth " << unn << " " << names[g];
        // Every crown point is 0.05 mm inside the input, in the band or above it.
        EXPECT_NEAR(parts["crown"]["output_to_input"]["mean"].get<double>(), 0.05, 1e-9);
    }
}

TEST_F(EvaluateSyntheticJaw, BoneDistancesMatchBruteForce) {
    const auto faces = boundaryFaces(*mesh_, kMandibleBoneLabel);
    std::vector<Triangle> output;
    for (const auto& f : faces) output.push_back(f.first);
    const std::vector<Triangle> input = triangles(input_->bone);
    std::vector<double> outIn, inOut;
    for (const auto& [p, tri] : areaSamples(output, 3000, 5)) outIn.push_back(bruteNearest(p, input).distance);
    for (const auto& [p, tri] : areaSamples(input, 1500, 6)) inOut.push_back(bruteNearest(p, output).distance);
    const auto& parts = domain("bone_mandible")["parts"];
    // Whole-bone mean, two-sided: area-weighted over both directions.
    double areaOut = 0, areaIn = 0;
    for (const Triangle& t : output) areaOut += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
    for (const Triangle& t : input) areaIn += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
    const double mean = (stats(outIn).mean * areaOut + stats(inOut).mean * areaIn) / (areaOut + areaIn);
    expectMatch(parts["whole"]["mean_mm"].get<double>(), mean, "bone two-sided mean");
    // By construction: the input block has no sockets, so the farthest output point is on a socket
    // wall (x = 4.4, y = 2) halfway between the input's bottom (z = 0) and top (z = 3.65), 1.825 mm
    // from both; the farthest input point is over a socket's middle, sqrt(0.8^2 + 0.05^2) from its rim.
    EXPECT_NEAR(parts["socket"]["output_to_input"]["max"].get<double>(), 1.825, 0.002);
    EXPECT_NEAR(parts["whole"]["hausdorff_mm"].get<double>(), 1.825, 0.002);
    const double inOutMax = std::max(parts["outer"]["input_to_output"]["max"].get<double>(),
                                     parts["socket"]["input_to_output"]["max"].get<double>());
    EXPECT_NEAR(inOutMax, std::sqrt(0.8 * 0.8 + 0.05 * 0.05), 0.002);
    EXPECT_GE(inOutMax, stats(inOut).max - 1e-9);
    EXPECT_GE(parts["whole"]["hausdorff_mm"].get<double>(), stats(outIn).max - 1e-9);
}

TEST_F(EvaluateSyntheticJaw, PdlThicknessMatchesBruteForce) {
    const auto& teeth = (*report_)["pdl_thickness"]["teeth"];
    ASSERT_EQ(teeth.size(), 2u);
    std::vector<double> all;
    for (const auto& row : teeth) {
        const int unn = row["tooth"].get<int>();
        std::vector<Triangle> toothSide, boneSide;
        for (const auto& [t, other] : boundaryFaces(*mesh_, pdlLabel(unn))) {
            if (other == toothLabel(unn)) toothSide.push_back(t);
            if (other == kMandibleBoneLabel) boneSide.push_back(t);
        }
        std::vector<double> v;
        for (const auto& [p, tri] : areaSamples(toothSide, 6000, 3)) v.push_back(bruteNearest(p, boneSide).distance);
        all.insert(all.end(), v.begin(), v.end());
        const Stats s = stats(v);
        const std::string what = "pdl " + std::to_string(unn);
        expectMatch(row["mean"].get<double>(), s.mean, what + " mean");
        expectMatch(row["p05"].get<double>(), s.p05, what + " p05");
        expectMatch(row["median"].get<double>(), s.median, what + " median");
        expectMatch(row["p95"].get<double>(), s.p95, what + " p95");
        expectMatch(row["min"].get<double>(), s.min, what + " min");
        expectMatch(row["max"].get<double>(), s.max, what + " max");
    }
    // By construction: tooth 25's PDL is 0.2 mm everywhere; tooth 24's is 0.4 mm on its +x side.
    EXPECT_NEAR(teeth[1]["min"].get<double>(), 0.2, 1e-9);
    EXPECT_NEAR(teeth[1]["max"].get<double>(), 0.2, 1e-9);
    EXPECT_NEAR(teeth[0]["max"].get<double>(), 0.4, 1e-6);
    const Stats jaw = stats(all);  // both tooth sides have the same area, so equal counts are area weights
    expectMatch((*report_)["pdl_thickness"]["jaw"]["mean"].get<double>(), jaw.mean, "jaw mean");
    expectMatch((*report_)["pdl_thickness"]["jaw"]["p95"].get<double>(), jaw.p95, "jaw p95");
    EXPECT_NEAR((*report_)["pdl_thickness"]["jaw"]["max"].get<double>(), 0.4, 1e-6);
}

TEST_F(EvaluateSyntheticJaw, SameReportForAnyThreadCount) {
    nlohmann::json one;
    {
        tbb::global_control only(tbb::global_control::max_allowed_parallelism, 1);
        one = evaluateMesh(*mesh_, input_);
    }
    nlohmann::json many = evaluateMesh(*mesh_, input_);  // default options: the cervical band too
    one.erase("seconds");
    many.erase("seconds");
    EXPECT_EQ(one.dump(), many.dump());
}

TEST(EvaluateMesh, BrokenMeshGetsAFailingVerdictOnly) {
    TetMesh m = syntheticJawMesh();
    m.tets[3][2] = static_cast<std::int32_t>(m.nodes.size() + 5);
    const nlohmann::json r = evaluateMesh(m, nullptr);
    EXPECT_EQ(r["verdict"]["status"], "fail");
    EXPECT_FALSE(r.contains("regions"));
    EXPECT_GT(r["validation"]["violations"]["bad_indices"].get<int>(), 0);
}
