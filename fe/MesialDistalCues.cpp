// Implements fe/MesialDistalCues.h; what it computes, its rules and its contract are documented there.
#include "fe/MesialDistalCues.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <array>
#include <map>
#include <numeric>

namespace jawmesh {
namespace {

constexpr double kElongatedVarianceRatio = 1.8;
constexpr double kCuspLineOffArchMaxDeg = 10.0;
constexpr double kOutlineOffArchMaxDeg = 30.0;

Vec3 perpendicularUnit(const Vec3& v, const Vec3& axis) {
    const Vec3 p = v - v.dot(axis) * axis;
    const double n = p.norm();
    return n > 0 ? Vec3(p / n) : Vec3::Zero();
}

/// Unsigned angle in degrees between two lines (0..90).
double lineAngleDeg(const Vec3& a, const Vec3& b) {
    return std::acos(std::clamp(std::abs(a.normalized().dot(b.normalized())), 0.0, 1.0)) * 180.0 / M_PI;
}

/// Derivative at parameter 0 of the least-squares polynomial of degree <= 2 through (s, value).
Vec3 slopeAtZero(const std::vector<double>& s, const std::vector<Vec3>& value) {
    const int degree = std::min<int>(2, static_cast<int>(s.size()) - 1);
    Eigen::MatrixXd design(s.size(), degree + 1);
    Eigen::MatrixXd rhs(s.size(), 3);
    for (std::size_t i = 0; i < s.size(); ++i) {
        for (int d = 0; d <= degree; ++d) design(static_cast<Eigen::Index>(i), d) = std::pow(s[i], d);
        rhs.row(static_cast<Eigen::Index>(i)) = value[i].transpose();
    }
    const Eigen::MatrixXd coefficients = design.colPivHouseholderQr().solve(rhs);
    return coefficients.row(1).transpose();
}

}  // namespace

std::vector<Vec3> archTangents(const std::vector<Vec3>& crownCentres, const Vec3& occlusalNormal, int window) {
    const int n = static_cast<int>(crownCentres.size());
    if (n < 2) return {};
    const Vec3 normal = occlusalNormal.normalized();
    std::vector<Vec3> planar(crownCentres.size());
    for (std::size_t i = 0; i < planar.size(); ++i) planar[i] = crownCentres[i] - crownCentres[i].dot(normal) * normal;
    std::vector<double> arcLength(planar.size(), 0.0);
    for (std::size_t i = 1; i < planar.size(); ++i) arcLength[i] = arcLength[i - 1] + (planar[i] - planar[i - 1]).norm();
    const int w = std::clamp(window, 2, n);
    std::vector<Vec3> tangents;
    for (int i = 0; i < n; ++i) {
        const int first = std::clamp(i - w / 2, 0, n - w);
        std::vector<double> s;
        std::vector<Vec3> points;
        for (int j = first; j < first + w; ++j) {
            s.push_back(arcLength[static_cast<std::size_t>(j)] - arcLength[static_cast<std::size_t>(i)]);
            points.push_back(planar[static_cast<std::size_t>(j)]);
        }
        const Vec3 slope = perpendicularUnit(slopeAtZero(s, points), normal);
        const Vec3 chord = planar[static_cast<std::size_t>(first + w - 1)] - planar[static_cast<std::size_t>(first)];
        tangents.push_back(slope.dot(chord) < 0 ? Vec3(-slope) : slope);
    }
    return tangents;
}

CrownOutline occlusalOutline(const SurfaceMesh& mesh, const Vec3& occlusal, double topFraction) {
    double top = -std::numeric_limits<double>::infinity(), bottom = -top;
    for (const Vec3& v : mesh.vertices) top = std::max(top, v.dot(occlusal)), bottom = std::min(bottom, v.dot(occlusal));
    const double cut = top - topFraction * (top - bottom);
    double area = 0;
    Vec3 first = Vec3::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    const Vec3 origin = mesh.vertices.empty() ? Vec3::Zero() : mesh.vertices.front();
    for (const Tri& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        const Vec3 centroid = (a + b + c) / 3.0;
        if (centroid.dot(occlusal) < cut) continue;
        const double w = 0.5 * (b - a).cross(c - a).norm();
        Vec3 p = centroid - origin;
        p -= p.dot(occlusal) * occlusal;
        area += w, first += w * p, second += w * p * p.transpose();
    }
    CrownOutline outline;
    if (!(area > 0)) return outline;
    const Vec3 mean = first / area;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(second / area - mean * mean.transpose());
    // The smallest eigenvalue (about 0) belongs to the long axis, removed above.
    outline.major = perpendicularUnit(eig.eigenvectors().col(2), occlusal);
    outline.minor = perpendicularUnit(eig.eigenvectors().col(1), occlusal);
    const double minorVariance = eig.eigenvalues()(1);
    outline.varianceRatio = minorVariance > 0 ? eig.eigenvalues()(2) / minorVariance : 1.0;
    return outline;
}

std::vector<Vec3> cuspTips(const SurfaceMesh& mesh, const Vec3& occlusal, int count, double radiusMm) {
    std::vector<std::size_t> order(mesh.vertices.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return mesh.vertices[a].dot(occlusal) > mesh.vertices[b].dot(occlusal);
    });
    // Vertices in descending height go into a hash grid of radius-sized cells; a vertex with no
    // earlier (higher) vertex within the radius is a local maximum.
    auto cellOf = [&](const Vec3& v) {
        return std::array<long, 3>{static_cast<long>(std::floor(v.x() / radiusMm)), static_cast<long>(std::floor(v.y() / radiusMm)),
                                   static_cast<long>(std::floor(v.z() / radiusMm))};
    };
    std::map<std::array<long, 3>, std::vector<std::size_t>> grid;
    std::vector<Vec3> tips;
    for (std::size_t i : order) {
        if (static_cast<int>(tips.size()) >= count) break;
        const Vec3& v = mesh.vertices[i];
        const std::array<long, 3> cell = cellOf(v);
        bool highest = true;
        for (long dx = -1; dx <= 1 && highest; ++dx)
            for (long dy = -1; dy <= 1 && highest; ++dy)
                for (long dz = -1; dz <= 1 && highest; ++dz) {
                    const auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
                    if (it == grid.end()) continue;
                    for (std::size_t j : it->second)
                        if ((mesh.vertices[j] - v).norm() < radiusMm) {
                            highest = false;
                            break;
                        }
                }
        grid[cell].push_back(i);
        if (highest) tips.push_back(v);
    }
    return tips;
}

MesialDistalChoice chooseMesialDistal(const SurfaceMesh& mesh, const Vec3& occlusal, const Vec3& archTangent,
                                      const Vec3& labial, bool molar) {
    const Vec3 arch = perpendicularUnit(archTangent, occlusal);
    MesialDistalChoice choice{arch, "arch", 0.0};
    auto take = [&](const Vec3& direction, const char* cue) {
        const Vec3 d = perpendicularUnit(direction, occlusal);
        choice = {d.dot(arch) < 0 ? Vec3(-d) : d, cue, lineAngleDeg(d, arch)};
    };
    const CrownOutline outline = occlusalOutline(mesh, occlusal);
    const Vec3 nearer = lineAngleDeg(outline.major, arch) <= lineAngleDeg(outline.minor, arch) ? outline.major : outline.minor;
    if (outline.varianceRatio >= kElongatedVarianceRatio && lineAngleDeg(nearer, arch) <= kOutlineOffArchMaxDeg) {
        take(nearer, "crown outline");
    } else if (molar) {
        std::vector<Vec3> tips = cuspTips(mesh, occlusal);
        if (tips.size() >= 2) {
            std::stable_sort(tips.begin(), tips.end(), [&](const Vec3& a, const Vec3& b) { return a.dot(labial) > b.dot(labial); });
            const Vec3 line = tips[0] - tips[1];
            if (lineAngleDeg(perpendicularUnit(line, occlusal), arch) <= kCuspLineOffArchMaxDeg) take(line, "buccal cusps");
        }
    }
    return choice;
}

}  // namespace jawmesh
