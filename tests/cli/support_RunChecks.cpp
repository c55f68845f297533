// Implements the test helpers of support_RunChecks.h (documented there).
#include "support_RunChecks.h"

#include "filters/TriangleGeometry.h"
#include "io/GmshReader.h"
#include "io/Labels.h"
#include "io/MeshIO.h"
#include "tet/RegionSurfaces.h"
#include "tet/TetFaceAdjacency.h"

#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

namespace jawmesh::test {

SurfaceDistance::SurfaceDistance(const SurfaceMesh& surface, double cellMm) : s_(surface), h_(cellMm) {
    BBox box;
    for (const Vec3& v : s_.vertices) box.extend(v);
    origin_ = box.min;
    for (int k = 0; k < 3; ++k) n_[k] = std::max(1, int(std::ceil((box.max[k] - box.min[k]) / h_)) + 1);
    cells_.resize(std::size_t(n_[0]) * std::size_t(n_[1]) * std::size_t(n_[2]));
    for (std::size_t t = 0; t < s_.triangles.size(); ++t) {
        BBox b;
        for (auto v : s_.triangles[t]) b.extend(s_.vertices[std::size_t(v)]);
        int lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::clamp(int((b.min[k] - origin_[k]) / h_), 0, n_[k] - 1);
            hi[k] = std::clamp(int((b.max[k] - origin_[k]) / h_), 0, n_[k] - 1);
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x)
                    cells_[(std::size_t(z) * std::size_t(n_[1]) + std::size_t(y)) * std::size_t(n_[0]) + std::size_t(x)].push_back(std::int32_t(t));
    }
}

double SurfaceDistance::operator()(const Vec3& p) const {
    int c[3];
    for (int k = 0; k < 3; ++k) c[k] = std::clamp(int((p[k] - origin_[k]) / h_), 0, n_[k] - 1);
    double best2 = std::numeric_limits<double>::infinity();
    const int maxRing = std::max({n_[0], n_[1], n_[2]});
    for (int r = 0; r <= maxRing; ++r) {
        for (int z = c[2] - r; z <= c[2] + r; ++z)
            for (int y = c[1] - r; y <= c[1] + r; ++y)
                for (int x = c[0] - r; x <= c[0] + r; ++x) {
                    if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != r) continue;  // shell only
                    if (x < 0 || y < 0 || z < 0 || x >= n_[0] || y >= n_[1] || z >= n_[2]) continue;
                    for (auto t : cells_[(std::size_t(z) * std::size_t(n_[1]) + std::size_t(y)) * std::size_t(n_[0]) + std::size_t(x)]) {
                        const Tri& f = s_.triangles[std::size_t(t)];
                        best2 = std::min(best2, squaredDistanceToTriangle(p, s_.vertices[std::size_t(f[0])], s_.vertices[std::size_t(f[1])],
                                                                          s_.vertices[std::size_t(f[2])]));
                    }
                }
        // every triangle not seen yet lies in cells at least r cells away from p's cell
        const double reach = double(r) * h_;
        if (best2 <= reach * reach) break;
    }
    return std::sqrt(best2);
}

double directedHausdorff(const SurfaceMesh& from, const SurfaceDistance& to, const std::function<bool(const Vec3&)>& skip) {
    // The vertices, then the triangle centroids; in parallel (a maximum: the same whatever the order).
    const std::size_t nv = from.vertices.size(), n = nv + from.triangles.size();
    const auto point = [&](std::size_t i) -> Vec3 {
        if (i < nv) return from.vertices[i];
        const Tri& f = from.triangles[i - nv];
        return (from.vertices[std::size_t(f[0])] + from.vertices[std::size_t(f[1])] + from.vertices[std::size_t(f[2])]) / 3.0;
    };
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, n, 4096), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double worst) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const Vec3 p = point(i);
                if (!skip || !skip(p)) worst = std::max(worst, to(p));
            }
            return worst;
        },
        [](double a, double b) { return std::max(a, b); });
}

namespace {

/// The faces of `mesh` between labels a and b, as a surface.
SurfaceMesh interfaceBetween(const TetMesh& mesh, const TetFaceAdjacency& adj, Label a, Label b) {
    SurfaceMesh s;
    s.vertices = mesh.nodes;  // unused nodes are harmless for distances from triangles
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        if (adj.groupSize(g) != 2) continue;
        const auto& f0 = adj.faces[std::size_t(adj.groupStart[g])];
        const auto& f1 = adj.faces[std::size_t(adj.groupStart[g]) + 1];
        const Label l0 = mesh.labels[std::size_t(f0.tet)], l1 = mesh.labels[std::size_t(f1.tet)];
        if ((l0 == a && l1 == b) || (l0 == b && l1 == a)) s.triangles.push_back({f0.key[0], f0.key[1], f0.key[2]});
    }
    return s;
}

SurfaceMesh compact(const SurfaceMesh& s) {
    SurfaceMesh out;
    std::vector<std::int32_t> map(s.vertices.size(), -1);
    for (Tri f : s.triangles) {
        for (auto& v : f) {
            if (map[std::size_t(v)] < 0) {
                map[std::size_t(v)] = std::int32_t(out.vertices.size());
                out.vertices.push_back(s.vertices[std::size_t(v)]);
            }
            v = map[std::size_t(v)];
        }
        out.triangles.push_back(f);
    }
    return out;
}

double twoSided(const SurfaceMesh& a, const SurfaceMesh& b, double cellMm) {
    const SurfaceDistance toA(a, cellMm), toB(b, cellMm);
    return std::max(directedHausdorff(a, toB), directedHausdorff(b, toA));
}

}  // namespace

RunFigures measureRun(const std::string& jawDir, const std::string& inputJawDir, const std::string& jaw,
                      const std::vector<int>& teethUnn) {
    RunFigures r;
    const TetMesh mesh = readGmsh(jawDir + "/volumetric_meshes/" + jaw + ".msh");
    r.validation = validateTetMesh(mesh, teethUnn);
    r.quality = measureQuality(mesh, 10.0);
    const TetFaceAdjacency adj = tetFaceAdjacency(mesh);
    const std::map<Label, SurfaceMesh> surfaces = regionSurfaces(mesh);
    const Label bone = jaw == "maxilla" ? kMaxillaBoneLabel : kMandibleBoneLabel;
    for (int unn : teethUnn) {
        const SurfaceMesh toothSide = compact(interfaceBetween(mesh, adj, toothLabel(unn), pdlLabel(unn)));
        const SurfaceMesh boneSide = compact(interfaceBetween(mesh, adj, pdlLabel(unn), bone));
        if (!toothSide.triangles.empty() && !boneSide.triangles.empty()) {
            const SurfaceDistance toBone(boneSide, 0.5);
            double sum = 0, area = 0;
            for (const Tri& f : toothSide.triangles) {
                const Vec3& a = toothSide.vertices[std::size_t(f[0])];
                const Vec3& b = toothSide.vertices[std::size_t(f[1])];
                const Vec3& c = toothSide.vertices[std::size_t(f[2])];
                const double w = 0.5 * (b - a).cross(c - a).norm();
                sum += w * toBone((a + b + c) / 3.0);
                area += w;
            }
            r.pdlThicknessMeanMm[unn] = area > 0 ? sum / area : 0.0;
        }
        const auto it = surfaces.find(toothLabel(unn));
        if (it != surfaces.end())
            r.toothHausdorffMm[unn] =
                twoSided(it->second, readSurface(inputJawDir + "/teeth/tooth_" + std::to_string(unn) + ".stl"), 0.5);
    }
    const auto it = surfaces.find(bone);
    if (it != surfaces.end()) r.boneHausdorffMm = twoSided(it->second, readSurface(inputJawDir + "/bone/" + jaw + ".stl"), 0.5);
    return r;
}

double boneHausdorffAwayFrom(const std::string& jawDir, const std::string& inputJawDir, const std::string& jaw,
                             const std::vector<std::pair<Vec3, double>>& away) {
    const TetMesh mesh = readGmsh(jawDir + "/volumetric_meshes/" + jaw + ".msh");
    const std::map<Label, SurfaceMesh> surfaces = regionSurfaces(mesh);
    const auto it = surfaces.find(jaw == "maxilla" ? kMaxillaBoneLabel : kMandibleBoneLabel);
    if (it == surfaces.end()) return 0;
    const SurfaceMesh input = readSurface(inputJawDir + "/bone/" + jaw + ".stl");
    const auto near = [&](const Vec3& p) {
        return std::any_of(away.begin(), away.end(), [&](const auto& ball) { return (p - ball.first).norm() < ball.second; });
    };
    const SurfaceDistance toOutput(it->second, 0.5), toInput(input, 0.5);
    return std::max(directedHausdorff(it->second, toInput, near), directedHausdorff(input, toOutput, near));
}

std::vector<int> teethIn(const std::string& teethDir) {
    std::vector<int> unn;
    for (const auto& e : std::filesystem::directory_iterator(teethDir)) {
        const std::string name = e.path().stem().string();  // tooth_<UNN>
        if (name.rfind("tooth_", 0) == 0) unn.push_back(std::stoi(name.substr(6)));
    }
    std::sort(unn.begin(), unn.end());
    return unn;
}

void expectSoundMesh(const RunFigures& f, const std::vector<int>& teeth) {
    std::printf("tets %zu, min dihedral %.2f deg (%zu below 10), bone Hausdorff %.3f mm\n", f.quality.tets, f.quality.minDihedralDeg,
                f.quality.belowDihedralThreshold, f.boneHausdorffMm);
    for (int u : teeth)
        std::printf("tooth %d: PDL thickness mean %.4f mm, Hausdorff %.3f mm\n", u, f.pdlThicknessMeanMm.at(u), f.toothHausdorffMm.at(u));
    EXPECT_TRUE(f.validation.valid()) << (f.validation.messages.empty() ? "" : f.validation.messages.front());
    EXPECT_EQ(f.validation.nonManifoldFaces + f.validation.coincidentFaces + f.validation.invertedTets +
                  f.validation.duplicateNodes + f.validation.degenerateTets,
              0u);
    EXPECT_TRUE(f.validation.missingTeeth.empty() && f.validation.missingPdls.empty());
    EXPECT_GE(f.quality.minDihedralDeg, 10.0);
    EXPECT_EQ(f.quality.belowDihedralThreshold, 0u);
}

void expectRunMeetsTargets(const RunFigures& f, const std::vector<int>& teeth, double boneBoundMm, double toothBoundMm,
                           std::size_t maxTets) {
    expectSoundMesh(f, teeth);
    EXPECT_LE(f.quality.tets, maxTets);
    for (int u : teeth) {
        EXPECT_NEAR(f.pdlThicknessMeanMm.at(u), 0.20, 0.01) << "tooth " << u;
        EXPECT_LE(f.toothHausdorffMm.at(u), toothBoundMm) << "tooth " << u;
    }
    EXPECT_LE(f.boneHausdorffMm, boneBoundMm);
}

namespace {

double tetVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return std::abs((b - a).cross(c - a).dot(d - a)) / 6.0;
}

/// The part of tet p where the signed heights h are negative (exact: a tet, a prism or the rest).
double clippedVolume(const std::array<Vec3, 4>& p, const std::array<double, 4>& h) {
    std::vector<int> below, above;
    for (int i = 0; i < 4; ++i) (h[i] < 0 ? below : above).push_back(i);
    const double whole = tetVolume(p[0], p[1], p[2], p[3]);
    const auto cut = [&](int i, int j) { return p[i] + (p[j] - p[i]) * (h[i] / (h[i] - h[j])); };
    if (below.empty()) return 0;
    if (above.empty()) return whole;
    if (below.size() == 1 || above.size() == 1) {
        const bool one = below.size() == 1;
        const int tip = one ? below[0] : above[0];
        const auto& rest = one ? above : below;
        const double corner = tetVolume(p[tip], cut(tip, rest[0]), cut(tip, rest[1]), cut(tip, rest[2]));
        return one ? corner : whole - corner;
    }
    // Two and two: a prism from edge (a, b) to the cut points towards c and d.
    const int a = below[0], b = below[1], c = above[0], d = above[1];
    const Vec3 ac = cut(a, c), ad = cut(a, d), bc = cut(b, c), bd = cut(b, d);
    return tetVolume(p[a], ac, ad, p[b]) + tetVolume(ac, ad, p[b], bc) + tetVolume(ad, p[b], bc, bd);
}

}  // namespace

double volumeBelowPlaneMm3(const TetMesh& mesh, const std::vector<Label>& labels, const Vec3& origin, const Vec3& up) {
    double total = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        if (std::find(labels.begin(), labels.end(), mesh.labels[t]) == labels.end()) continue;
        std::array<Vec3, 4> p;
        std::array<double, 4> h;
        for (int k = 0; k < 4; ++k) {
            p[k] = mesh.nodes[mesh.tets[t][k]];
            h[k] = (p[k] - origin).dot(up);
        }
        total += clippedVolume(p, h);
    }
    return total;
}

std::vector<double> crestHeightsMm(const TetMesh& mesh, Label bone, int unn, const Vec3& origin, const Vec3& up,
                                   double reachMm) {
    const std::map<Label, SurfaceMesh> surfaces = regionSurfaces(mesh);
    const SurfaceMesh& tooth = surfaces.at(toothLabel(unn));
    const SurfaceDistance toTooth(tooth, 0.5);
    Vec3 lo = tooth.vertices[0], hi = lo;
    for (const Vec3& v : tooth.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const Vec3 u = (std::abs(up.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(up).normalized(), w = up.cross(u);
    constexpr int kBins = 36;
    std::vector<double> top(kBins, -std::numeric_limits<double>::infinity());
    for (const Vec3& v : surfaces.at(bone).vertices) {
        if (((v - lo).array() < -reachMm).any() || ((v - hi).array() > reachMm).any()) continue;
        if (toTooth(v) > reachMm) continue;
        const Vec3 d = v - origin;
        const double phi = std::atan2(d.dot(w), d.dot(u)) + M_PI;
        const int bin = std::min(kBins - 1, int(phi / (2 * M_PI) * kBins));
        top[std::size_t(bin)] = std::max(top[std::size_t(bin)], d.dot(up));
    }
    std::vector<double> heights;
    for (double h : top)
        if (std::isfinite(h)) heights.push_back(h);
    return heights;
}

}  // namespace jawmesh::test
