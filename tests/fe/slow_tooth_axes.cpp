// Computed tooth axes against the clinician-provided ones of real teeth (Open-Full-Jaw patient 26,
// ../shared/data/p26-maxilla-teeth): long axis within 10 degrees, labial axis within 20 degrees;
// and their plausibility on real teeth without provided axes (../shared/data/openmandible).
#include "fe/ToothAxesFromShape.h"
#include "io/Case.h"
#include "support/TestData.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

namespace jawmesh {
namespace {

/// Issue #26's bounds, on every tooth: long axis within 8 degrees, labial axis within 12. Measured
/// (clinical crown axis, mesial-distal from the crown's cues or the arch, fe/MesialDistalCues.h):
/// long median 5.2, worst 7.3 (tooth 1, a third molar); labial worst 9.5 (tooth 11). With the
/// neighbour chord as mesial-distal axis the labial axis was 17.7 off on tooth 10, a lateral
/// incisor rotated against the arch.
void expectAxesAgree(const JawSurfaces& jaw, const std::map<int, ToothAxes>& computed) {
    ASSERT_EQ(computed.size(), jaw.teeth.size());
    std::vector<double> longs;
    double worstLabial = 0;
    for (const auto& [unn, given] : jaw.axes) {
        SCOPED_TRACE("tooth " + std::to_string(unn));
        ASSERT_TRUE(computed.count(unn));
        const ToothAxes& c = computed.at(unn);
        const double longDeg = angleDeg(c.occlusal, given.occlusal);
        const double labialDeg = angleDeg(c.labial, given.labial);
        const double distalDeg = angleDeg(c.mesialDistal, given.mesialDistal);
        const double centreMm = (c.crownCentre - given.crownCentre).norm();
        std::cout << "tooth " << unn << ": long " << longDeg << " deg, labial " << labialDeg << " deg, distal "
                  << distalDeg << " deg, crown centre " << centreMm << " mm apart\n";
        EXPECT_LT(longDeg, 8.0);
        EXPECT_LT(labialDeg, 12.0);
        EXPECT_LT(distalDeg, 12.0);
        EXPECT_LT(centreMm, 2.0);
        longs.push_back(longDeg);
        worstLabial = std::max(worstLabial, labialDeg);
    }
    std::sort(longs.begin(), longs.end());
    std::cout << "long axis: median " << longs[longs.size() / 2] << " deg, worst " << longs.back()
              << " deg; labial worst " << worstLabial << " deg\n";
}

/// The one jaw of a shared case (throws when it has several or none).
JawCase onlyJawOf(const std::string& caseDir) {
    const CaseInfo info = discoverCase(caseDir);
    if (info.jaws.size() != 1) throw std::runtime_error(caseDir + ": expected one jaw, found " + std::to_string(info.jaws.size()));
    return info.jaws[0];
}

TEST(ToothAxesFromShape, AgreesWithTheProvidedAxesOfRealMaxillaryTeeth) {
    const std::string caseDir = test::sharedData("p26-maxilla-teeth");
    JAWMESH_REQUIRE_SHARED(caseDir);
    const JawSurfaces jaw = loadJaw(onlyJawOf(caseDir));
    ASSERT_EQ(jaw.axes.size(), 15u);
    // With the bone deciding the occlusal side, and from the tooth shapes alone.
    std::vector<std::string> notes;
    expectAxesAgree(jaw, toothAxesFromShape(jaw.teeth, jaw.jaw, jaw.bone, {}, &notes));
    for (const std::string& n : notes) {
        EXPECT_EQ(n.find("no labial crown face"), std::string::npos) << n;
        EXPECT_EQ(n.find("uncertain"), std::string::npos) << n;  // real teeth agree with their neighbours
    }
    expectAxesAgree(jaw, toothAxesFromShape(jaw.teeth, jaw.jaw, SurfaceMesh()));
}

/// Teeth without provided axes (the OpenMandible mandible, another person): the computed axes must
/// be anatomically plausible. Long axes point to the occlusal side (+z: crowns above the roots in
/// this scan) and within 30 degrees of each neighbour's (lower molars lean lingually against the
/// premolars, the curve of Wilson: first molar 19 against premolar 20 measures 25.0; the wrong axis
/// of a held-out mandible's last molar was 44 off); the labial axis points out of the arch
/// (away from the tongue side, where the arch's centroid lies) and the crown centre lies on the
/// crown side of the tooth's volume centroid.
TEST(ToothAxesFromShape, PlausibleOnTheRealMandibleWithoutProvidedAxes) {
    const std::string caseDir = test::sharedData("openmandible");
    JAWMESH_REQUIRE_SHARED(caseDir);
    const JawSurfaces jaw = loadJaw(onlyJawOf(caseDir));
    ASSERT_TRUE(jaw.axes.empty());
    std::vector<std::string> notes;
    const auto axes = toothAxesFromShape(jaw.teeth, jaw.jaw, jaw.bone, {}, &notes);
    ASSERT_EQ(axes.size(), 14u);
    for (const std::string& n : notes) {
        EXPECT_EQ(n.find("no labial crown face"), std::string::npos) << n;
        EXPECT_EQ(n.find("uncertain"), std::string::npos) << n;
    }
    Vec3 archCentre = Vec3::Zero();
    for (const auto& [unn, a] : axes) archCentre += a.crownCentre / static_cast<double>(axes.size());
    for (auto it = axes.begin(); it != axes.end(); ++it) {
        const auto& [unn, a] = *it;
        SCOPED_TRACE("tooth " + std::to_string(unn));
        EXPECT_GT(a.occlusal.z(), 0.7);
        if (std::next(it) != axes.end()) {
            const double toNext = angleDeg(a.occlusal, std::next(it)->second.occlusal);
            std::cout << "tooth " << unn << ": long axis " << a.occlusal.transpose() << ", " << toNext << " deg to the next\n";
            EXPECT_LT(toNext, 30.0);
        }
        Vec3 outward = a.crownCentre - archCentre;
        outward -= outward.dot(a.occlusal) * a.occlusal;
        EXPECT_GT(a.labial.dot(outward.normalized()), 0.3);
        EXPECT_NEAR(a.labial.dot(a.occlusal), 0.0, 1e-9);
        EXPECT_NEAR(a.mesialDistal.dot(a.occlusal), 0.0, 1e-9);
        double volume = 0;
        Vec3 moment = Vec3::Zero();
        for (const Tri& t : jaw.teeth.at(unn).triangles) {
            const Vec3& p = jaw.teeth.at(unn).vertices[static_cast<std::size_t>(t[0])];
            const Vec3& q = jaw.teeth.at(unn).vertices[static_cast<std::size_t>(t[1])];
            const Vec3& r = jaw.teeth.at(unn).vertices[static_cast<std::size_t>(t[2])];
            const double v = p.dot(q.cross(r)) / 6.0;
            volume += v, moment += v * (p + q + r) / 4.0;
        }
        EXPECT_GT((a.crownCentre - moment / volume).dot(a.occlusal), 1.0);
    }
}

TEST(AxesCommand, PrintsTheCaseAxesInTheirJsonShape) {
    const std::string caseDir = test::sharedData("p26-maxilla-teeth");
    JAWMESH_REQUIRE_SHARED(caseDir);
    const auto out = test::scratchDir("axes-command");
    const std::string cmd = std::string(JAWMESH_BINARY) + " --quiet axes " + caseDir + " --computed --json > " + (out / "axes.json").string();
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::ifstream in(out / "axes.json");
    const auto axes = nlohmann::json::parse(in);
    EXPECT_EQ(axes.size(), 15u);
    for (const auto& [unn, a] : axes.items())
        for (const char* k : {"c", "x", "y", "z"}) EXPECT_EQ(a.at(k).size(), 3u) << unn << " " << k;
}

}  // namespace
}  // namespace jawmesh
