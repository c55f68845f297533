// Implements filters/CrossSection.h; what it computes, its rules and its contract are documented there.
#include "filters/CrossSection.h"

#include "io/Error.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <set>

namespace jawmesh {
namespace {

constexpr int kMaxPixels = 4096;

const Vec3& node(const TetMesh& m, const Tet& t, std::size_t k) { return m.nodes[static_cast<std::size_t>(t[k])]; }

/// Volume-weighted centroid and covariance of the tets selected by `keep`.
struct Moments {
    double volume = 0;
    Vec3 centroid = Vec3::Zero();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

template <typename Keep>
Moments tetMoments(const TetMesh& mesh, Keep&& keep) {
    Moments m;
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        if (!keep(mesh.labels[t])) continue;
        const Tet& e = mesh.tets[t];
        const Vec3 c = (node(mesh, e, 0) + node(mesh, e, 1) + node(mesh, e, 2) + node(mesh, e, 3)) / 4.0;
        const double v = std::abs((node(mesh, e, 1) - node(mesh, e, 0))
                                      .dot((node(mesh, e, 2) - node(mesh, e, 0)).cross(node(mesh, e, 3) - node(mesh, e, 0)))) / 6.0;
        m.volume += v;
        m.centroid += v * c;
        second += v * c * c.transpose();
    }
    if (m.volume <= 0) return m;
    m.centroid /= m.volume;
    m.covariance = second / m.volume - m.centroid * m.centroid.transpose();
    return m;
}

/// Eigenvectors of a covariance, largest spread first.
std::array<Vec3, 3> principalAxes(const Eigen::Matrix3d& covariance) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    return {Vec3(solver.eigenvectors().col(2)), Vec3(solver.eigenvectors().col(1)), Vec3(solver.eigenvectors().col(0))};
}

/// Spread of the selected tets' nodes along `axis` around `centre`: (min, max).
template <typename Keep>
std::pair<double, double> extentAlong(const TetMesh& mesh, Keep&& keep, const Vec3& centre, const Vec3& axis) {
    double lo = 0, hi = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        if (!keep(mesh.labels[t])) continue;
        for (std::size_t k = 0; k < 4; ++k) {
            const double s = (node(mesh, mesh.tets[t], k) - centre).dot(axis);
            lo = std::min(lo, s);
            hi = std::max(hi, s);
        }
    }
    return {lo, hi};
}

bool isKind(Label l, LabelKind kind) { return labelKind(l) == kind; }

/// Tooth long axis oriented away from its PDL (occlusally); with no PDL, away from the bone.
Vec3 occlusalAxis(const TetMesh& mesh, int unn, const Moments& tooth) {
    Vec3 axis = principalAxes(tooth.covariance)[0];
    Moments root = tetMoments(mesh, [&](Label l) { return l == pdlLabel(unn); });
    if (root.volume <= 0) root = tetMoments(mesh, [](Label l) { return isKind(l, LabelKind::Bone); });
    if (root.volume > 0 && (tooth.centroid - root.centroid).dot(axis) < 0) axis = -axis;
    return axis;
}

}  // namespace

SectionRaster rasterizeSection(const TetMesh& mesh, const SectionPlane& plane, double pixelMm) {
    if (!(pixelMm > 0)) throw Error("cross-section: pixel size must be positive");
    if (std::abs(plane.right.norm() - 1) > 1e-6 || std::abs(plane.up.norm() - 1) > 1e-6 || std::abs(plane.right.dot(plane.up)) > 1e-6)
        throw Error("cross-section: plane directions must be orthonormal");
    SectionRaster r;
    r.pixelMm = pixelMm;
    r.width = std::clamp(static_cast<int>(std::ceil(plane.widthMm / pixelMm)), 1, kMaxPixels);
    r.height = std::clamp(static_cast<int>(std::ceil(plane.heightMm / pixelMm)), 1, kMaxPixels);
    r.label.assign(static_cast<std::size_t>(r.width) * static_cast<std::size_t>(r.height), kOutsideLabel);
    r.edge.assign(r.label.size(), 0);
    const Vec3 normal = plane.right.cross(plane.up);
    // Pixel coordinates of a point of the plane (pixel centres at integer + 0.5).
    const auto toPixel = [&](const Vec3& p) {
        const Vec3 d = p - plane.centreMm;
        return Eigen::Vector2d((d.dot(plane.right) + 0.5 * plane.widthMm) / pixelMm, (0.5 * plane.heightMm - d.dot(plane.up)) / pixelMm);
    };
    const auto markEdge = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
        const int steps = static_cast<int>(std::ceil(2.0 * (b - a).norm())) + 1;
        for (int s = 0; s <= steps; ++s) {
            const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(s) / steps);
            const int x = static_cast<int>(std::floor(p.x())), y = static_cast<int>(std::floor(p.y()));
            if (x >= 0 && y >= 0 && x < r.width && y < r.height)
                r.edge[static_cast<std::size_t>(y) * static_cast<std::size_t>(r.width) + static_cast<std::size_t>(x)] = 1;
        }
    };
    static const int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& e = mesh.tets[t];
        std::array<double, 4> s;
        int above = 0;
        for (std::size_t k = 0; k < 4; ++k) {
            s[k] = (node(mesh, e, k) - plane.centreMm).dot(normal);
            above += s[k] >= 0;  // on the plane counts as above: each crossing edge is counted once
        }
        if (above == 0 || above == 4) continue;
        std::array<Eigen::Vector2d, 4> poly;
        int n = 0;
        for (const auto& ed : kEdges) {
            const double sa = s[static_cast<std::size_t>(ed[0])], sb = s[static_cast<std::size_t>(ed[1])];
            if ((sa >= 0) == (sb >= 0)) continue;
            const Vec3& a = node(mesh, e, static_cast<std::size_t>(ed[0]));
            const Vec3& b = node(mesh, e, static_cast<std::size_t>(ed[1]));
            poly[static_cast<std::size_t>(n++)] = toPixel(a + (sa / (sa - sb)) * (b - a));
        }
        // 3 or 4 crossing points, convex: order them around their centre.
        Eigen::Vector2d centre = Eigen::Vector2d::Zero();
        for (int k = 0; k < n; ++k) centre += poly[static_cast<std::size_t>(k)];
        centre /= n;
        std::array<double, 4> angle{};
        for (int k = 0; k < n; ++k)
            angle[static_cast<std::size_t>(k)] = std::atan2(poly[static_cast<std::size_t>(k)].y() - centre.y(), poly[static_cast<std::size_t>(k)].x() - centre.x());
        for (int k = 1; k < n; ++k)  // insertion sort of at most 4 points by angle
            for (int j = k; j > 0 && angle[static_cast<std::size_t>(j)] < angle[static_cast<std::size_t>(j - 1)]; --j) {
                std::swap(angle[static_cast<std::size_t>(j)], angle[static_cast<std::size_t>(j - 1)]);
                std::swap(poly[static_cast<std::size_t>(j)], poly[static_cast<std::size_t>(j - 1)]);
            }
        double x0 = poly[0].x(), x1 = x0, y0 = poly[0].y(), y1 = y0;
        for (int k = 1; k < n; ++k) {
            x0 = std::min(x0, poly[static_cast<std::size_t>(k)].x());
            x1 = std::max(x1, poly[static_cast<std::size_t>(k)].x());
            y0 = std::min(y0, poly[static_cast<std::size_t>(k)].y());
            y1 = std::max(y1, poly[static_cast<std::size_t>(k)].y());
        }
        if (x1 < 0 || y1 < 0 || x0 > r.width || y0 > r.height) continue;
        const int px0 = std::max(0, static_cast<int>(std::floor(x0 - 0.5))), px1 = std::min(r.width - 1, static_cast<int>(std::ceil(x1)));
        const int py0 = std::max(0, static_cast<int>(std::floor(y0 - 0.5))), py1 = std::min(r.height - 1, static_cast<int>(std::ceil(y1)));
        for (int y = py0; y <= py1; ++y)
            for (int x = px0; x <= px1; ++x) {
                const Eigen::Vector2d p(x + 0.5, y + 0.5);
                bool inside = true;
                for (int k = 0; k < n && inside; ++k) {
                    const Eigen::Vector2d& a = poly[static_cast<std::size_t>(k)];
                    const Eigen::Vector2d& b = poly[static_cast<std::size_t>((k + 1) % n)];
                    inside = (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x()) >= 0;
                }
                if (inside) r.label[static_cast<std::size_t>(y) * static_cast<std::size_t>(r.width) + static_cast<std::size_t>(x)] = mesh.labels[t];
            }
        for (int k = 0; k < n; ++k) markEdge(poly[static_cast<std::size_t>(k)], poly[static_cast<std::size_t>((k + 1) % n)]);
    }
    return r;
}

std::optional<SectionPlane> toothSectionPlane(const TetMesh& mesh, int unn) {
    const Label tooth = toothLabel(unn);
    const Moments m = tetMoments(mesh, [&](Label l) { return l == tooth; });
    if (m.volume <= 0) return std::nullopt;
    const Vec3 up = occlusalAxis(mesh, unn, m);
    // The arch tangent from the neighbouring teeth in UNN order (UNN runs along the arch); only
    // those two are measured (each is a pass over the mesh).
    std::set<int> unns;
    for (Label l : mesh.labels)
        if (isKind(l, LabelKind::Tooth)) unns.insert(labelUnn(l));
    const auto self = unns.find(unn);
    const auto centreOf = [&](int u) {
        return u == unn ? m.centroid : tetMoments(mesh, [&](Label l) { return l == toothLabel(u); }).centroid;
    };
    const Vec3 before = centreOf(self == unns.begin() ? unn : *std::prev(self));
    const Vec3 after = centreOf(std::next(self) == unns.end() ? unn : *std::next(self));
    Vec3 tangent = after - before;
    tangent -= tangent.dot(up) * up;
    Vec3 right = up.cross(tangent);  // buccolingual
    if (tangent.norm() < 1e-9) {  // a single tooth: its axis of smallest spread
        right = principalAxes(m.covariance)[2];
        right -= right.dot(up) * up;
    }
    right.normalize();
    const auto [lo, hi] = extentAlong(mesh, [&](Label l) { return l == tooth; }, m.centroid, up);
    SectionPlane p;
    p.up = up;
    p.right = right;
    p.heightMm = 1.3 * (hi - lo);
    p.widthMm = 0.8 * p.heightMm;
    p.centreMm = m.centroid + 0.5 * (hi + lo) * up;
    return p;
}

std::optional<SectionPlane> archSectionPlane(const TetMesh& mesh) {
    const auto all = [](Label) { return true; };
    const Moments whole = tetMoments(mesh, all);
    if (whole.volume <= 0) return std::nullopt;
    std::map<int, bool> teeth;
    for (Label l : mesh.labels)
        if (isKind(l, LabelKind::Tooth)) teeth[labelUnn(l)] = true;
    Vec3 normal = Vec3::Zero();
    for (const auto& [unn, present] : teeth) {
        const Moments m = tetMoments(mesh, [&](Label l) { return l == toothLabel(unn); });
        normal += occlusalAxis(mesh, unn, m);
    }
    if (normal.norm() < 1e-9) normal = principalAxes(whole.covariance)[2];
    normal.normalize();
    Moments at = tetMoments(mesh, [](Label l) { return isKind(l, LabelKind::Pdl); });
    if (at.volume <= 0) at = tetMoments(mesh, [](Label l) { return isKind(l, LabelKind::Tooth); });
    if (at.volume <= 0) at = whole;
    // The arch's widest in-plane spread: principal axes of the covariance projected on the plane.
    const Eigen::Matrix3d project = Eigen::Matrix3d::Identity() - normal * normal.transpose();
    Vec3 right = principalAxes(project * whole.covariance * project)[0];
    right = (right - right.dot(normal) * normal).normalized();
    const Vec3 up = normal.cross(right);
    const auto [rlo, rhi] = extentAlong(mesh, all, at.centroid, right);
    const auto [ulo, uhi] = extentAlong(mesh, all, at.centroid, up);
    SectionPlane p;
    p.right = right;
    p.up = up;
    p.widthMm = 1.05 * (rhi - rlo);
    p.heightMm = 1.05 * (uhi - ulo);
    p.centreMm = at.centroid + 0.5 * (rhi + rlo) * right + 0.5 * (uhi + ulo) * up;
    return p;
}

}  // namespace jawmesh
