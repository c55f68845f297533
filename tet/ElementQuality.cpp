// Implements tet/ElementQuality.h; what it computes, its rules and its contract are documented there.
#include "tet/ElementQuality.h"

#include "io/Angles.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace jawmesh {

std::map<Label, double> labelVolumesMm3(const TetMesh& mesh) {
    std::map<Label, double> volumes;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& e = mesh.tets[t];
        volumes[mesh.labels[t]] += signedTetVolume(mesh.nodes[std::size_t(e[0])], mesh.nodes[std::size_t(e[1])],
                                                   mesh.nodes[std::size_t(e[2])], mesh.nodes[std::size_t(e[3])]);
    }
    return volumes;
}

TetShape tetShape(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    TetShape s;
    const Vec3 u = b - a, v = c - a, w = d - a;
    const double det = u.dot(v.cross(w));
    s.signedVolume = det / 6.0;

    // Outward area vectors of the faces opposite each vertex (for det > 0).
    const std::array<Vec3, 4> n = {(c - b).cross(d - b), (d - a).cross(c - a), (b - a).cross(d - a),
                                   (c - a).cross(b - a)};
    double minAngle = kPi, maxAngle = 0;
    for (int k = 0; k < 4; ++k) {
        for (int l = k + 1; l < 4; ++l) {
            const double nn = n[k].norm() * n[l].norm();
            double angle;
            if (nn <= 0) {
                angle = 0;
            } else {
                const double cosine = std::clamp(n[k].dot(n[l]) / nn, -1.0, 1.0);
                angle = kPi - std::acos(cosine);  // interior dihedral at the edge the two faces share
            }
            minAngle = std::min(minAngle, angle);
            maxAngle = std::max(maxAngle, angle);
        }
    }
    if (det == 0) {  // flat: some dihedral is 0 and another 180 whatever the normals say
        minAngle = 0;
        maxAngle = kPi;
    }
    s.minDihedralDeg = minAngle * 180.0 / kPi;
    s.maxDihedralDeg = maxAngle * 180.0 / kPi;

    const double shortest2 = std::min({u.squaredNorm(), v.squaredNorm(), w.squaredNorm(), (c - b).squaredNorm(),
                                       (d - b).squaredNorm(), (d - c).squaredNorm()});
    const double sumEdge2 = u.squaredNorm() + v.squaredNorm() + w.squaredNorm() + (c - b).squaredNorm() +
                            (d - b).squaredNorm() + (d - c).squaredNorm();
    if (det == 0 || shortest2 == 0) {
        s.radiusEdgeRatio = std::numeric_limits<double>::infinity();
        return s;  // radius and volume-edge ratios stay 0
    }
    const Vec3 centre =
        (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / (2.0 * det);
    const double circumradius = centre.norm();
    s.radiusEdgeRatio = circumradius / std::sqrt(shortest2);
    // Inradius = 3 V / total face area; the face area vectors n[] are twice the areas.
    const double area = 0.5 * (n[0].norm() + n[1].norm() + n[2].norm() + n[3].norm());
    const double volume = std::abs(det) / 6.0;
    s.radiusRatio = 3.0 * (3.0 * volume / area) / circumradius;
    const double rmsEdge = std::sqrt(sumEdge2 / 6.0);
    s.volumeEdgeRatio = 6.0 * std::sqrt(2.0) * volume / (rmsEdge * rmsEdge * rmsEdge);
    return s;
}

std::vector<TetShape> tetShapes(const TetMesh& mesh) {
    std::vector<TetShape> shapes(mesh.tets.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, shapes.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            const Tet& e = mesh.tets[t];
            shapes[t] = tetShape(mesh.nodes[static_cast<std::size_t>(e[0])], mesh.nodes[static_cast<std::size_t>(e[1])],
                                 mesh.nodes[static_cast<std::size_t>(e[2])], mesh.nodes[static_cast<std::size_t>(e[3])]);
        }
    });
    return shapes;
}

QualityStats measureQuality(const TetMesh& mesh, double dihedralThresholdDeg) {
    QualityStats q;
    const std::size_t n = mesh.tets.size();
    q.tets = n;
    if (n == 0) return q;
    const std::vector<TetShape> shapes = tetShapes(mesh);
    double sum = 0;
    for (std::size_t t = 0; t < n; ++t) {
        const TetShape& s = shapes[t];
        if (s.minDihedralDeg < q.minDihedralDeg) {
            q.minDihedralDeg = s.minDihedralDeg;
            q.worstTet = static_cast<std::int64_t>(t);
        }
        q.maxDihedralDeg = std::max(q.maxDihedralDeg, s.maxDihedralDeg);
        q.maxRadiusEdge = std::max(q.maxRadiusEdge, s.radiusEdgeRatio);
        sum += s.radiusEdgeRatio;
        if (s.minDihedralDeg < dihedralThresholdDeg) ++q.belowDihedralThreshold;
        if (t < mesh.labels.size()) {
            const Label l = mesh.labels[t];
            auto it = q.minDihedralByLabel.find(l);
            if (it == q.minDihedralByLabel.end()) {
                q.minDihedralByLabel[l] = s.minDihedralDeg;
                q.maxRadiusEdgeByLabel[l] = s.radiusEdgeRatio;
            } else {
                it->second = std::min(it->second, s.minDihedralDeg);
                double& r = q.maxRadiusEdgeByLabel[l];
                r = std::max(r, s.radiusEdgeRatio);
            }
        }
    }
    q.meanRadiusEdge = sum / static_cast<double>(n);
    return q;
}

nlohmann::json toJson(const QualityStats& q) {
    return {{"min_dihedral_deg", q.minDihedralDeg},
            {"max_dihedral_deg", q.maxDihedralDeg},
            {"max_radius_edge", q.maxRadiusEdge},
            {"tets_below_min_dihedral", q.belowDihedralThreshold}};
}

}  // namespace jawmesh
