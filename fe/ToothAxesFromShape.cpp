// Implements fe/ToothAxesFromShape.h; what it computes, its rules and its contract are documented there.
#include "fe/ToothAxesFromShape.h"

#include "fe/MesialDistalCues.h"
#include "filters/RayTriangle.h"
#include "io/Error.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace jawmesh {
namespace {

/// Volume, first and second moments of the region bounded by triangles, from tets to `origin`.
struct Moments {
    double volume = 0;
    Vec3 first = Vec3::Zero();                     ///< integral of (x - origin)
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  ///< integral of (x - origin)(x - origin)^T
    void addTriangle(const Vec3& a, const Vec3& b, const Vec3& c) {
        const double v = a.dot(b.cross(c)) / 6.0;
        const Vec3 s = a + b + c;
        volume += v;
        first += v * s / 4.0;
        second += v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
};

Moments momentsOf(const SurfaceMesh& mesh, const Vec3& origin) {
    Moments m;
    for (const Tri& t : mesh.triangles)
        m.addTriangle(mesh.vertices[static_cast<std::size_t>(t[0])] - origin, mesh.vertices[static_cast<std::size_t>(t[1])] - origin,
                      mesh.vertices[static_cast<std::size_t>(t[2])] - origin);
    return m;
}

/// Volume centroid of the part of a closed mesh where (x - planePoint) . axis >= 0: triangles are
/// clipped and tets taken from a point on the plane, so the cut face adds nothing.
Vec3 clippedCentroid(const SurfaceMesh& mesh, const Vec3& planePoint, const Vec3& axis, double orientation) {
    Moments m;
    for (const Tri& t : mesh.triangles) {
        std::array<Vec3, 3> p;
        for (int i = 0; i < 3; ++i) p[static_cast<std::size_t>(i)] = mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])] - planePoint;
        std::vector<Vec3> poly;
        for (int i = 0; i < 3; ++i) {
            const Vec3& a = p[static_cast<std::size_t>(i)];
            const Vec3& b = p[static_cast<std::size_t>((i + 1) % 3)];
            const double da = a.dot(axis), db = b.dot(axis);
            if (da >= 0) poly.push_back(a);
            if ((da >= 0) != (db >= 0)) poly.push_back(a + (b - a) * (da / (da - db)));
        }
        for (std::size_t k = 1; k + 1 < poly.size(); ++k) m.addTriangle(poly[0], poly[k], poly[k + 1]);
    }
    m.volume *= orientation;
    m.first *= orientation;
    return m.volume > 0 ? Vec3(planePoint + m.first / m.volume) : planePoint;
}

struct Shape {
    Vec3 centroid;
    Vec3 longAxis;       ///< unit, sense not yet decided
    double crownVote = 0;  ///< > 0: the crown lies along +longAxis (bulk or bone)
    double orientation = 1;  ///< -1 when the mesh is oriented inward
    BBox box;
};

Shape shapeOf(int unn, const SurfaceMesh& mesh) {
    if (mesh.triangles.empty()) throw Error("tooth " + std::to_string(unn) + ": empty surface, no axes");
    Shape s;
    s.box = boundingBox(mesh);
    const Vec3 origin = 0.5 * (s.box.min + s.box.max);
    Moments m = momentsOf(mesh, origin);
    if (m.volume < 0) {
        s.orientation = -1;
        m.volume = -m.volume, m.first = -m.first, m.second = -m.second;
    }
    if (!(m.volume > 1e-9)) throw Error("tooth " + std::to_string(unn) + ": surface encloses no volume, no axes");
    const Vec3 mean = m.first / m.volume;
    s.centroid = origin + mean;
    const Eigen::Matrix3d covariance = m.second / m.volume - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(covariance);
    s.longAxis = eig.eigenvectors().col(2).normalized();
    // The crown is the bulky end: the volume centroid lies on its side of the mid-length.
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Tri& t : mesh.triangles)
        for (std::int32_t v : t) {
            const double h = (mesh.vertices[static_cast<std::size_t>(v)] - s.centroid).dot(s.longAxis);
            lo = std::min(lo, h), hi = std::max(hi, h);
        }
    s.crownVote = -(lo + hi) / 2.0;  // centroid (0) minus the mid-length
    return s;
}

/// Mean outward unit normal of the labial face of a crown: the faces facing labially within
/// radiusMm of the outermost point where the ray from `centre` along `labial` leaves the tooth.
/// False when the ray misses the tooth or no face there faces labially.
bool labialFaceNormal(const SurfaceMesh& mesh, double orientation, const Vec3& centre, const Vec3& labial, double radiusMm,
                      Vec3& normal) {
    double exit = 0;
    for (const Tri& t : mesh.triangles) {
        const double hit = rayTriangleHit(centre, labial, mesh.vertices[static_cast<std::size_t>(t[0])],
                                          mesh.vertices[static_cast<std::size_t>(t[1])], mesh.vertices[static_cast<std::size_t>(t[2])]);
        if (std::isfinite(hit)) exit = std::max(exit, hit);
    }
    if (exit <= 0) return false;
    const Vec3 point = centre + exit * labial;
    Vec3 sum = Vec3::Zero();
    for (const Tri& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        const Vec3 areaNormal = 0.5 * orientation * (b - a).cross(c - a);  // outward, |.| = area
        // Facing labially: a thin crown's lingual face can lie within the radius.
        if (((a + b + c) / 3.0 - point).norm() <= radiusMm && areaNormal.dot(labial) > 0) sum += areaNormal;
    }
    if (sum.norm() <= 0) return false;
    normal = sum.normalized();
    return true;
}

/// The crown centre for a long axis `occlusal`: the volume centroid of the occlusal crownFraction
/// of the tooth's length.
Vec3 crownCentreOf(const SurfaceMesh& mesh, const Shape& s, const Vec3& occlusal, double crownFraction) {
    double top = -std::numeric_limits<double>::infinity(), bottom = -top;
    for (const Vec3& v : mesh.vertices) {
        const double h = (v - s.centroid).dot(occlusal);
        top = std::max(top, h), bottom = std::min(bottom, h);
    }
    const Vec3 cut = s.centroid + (top - crownFraction * (top - bottom)) * occlusal;
    return clippedCentroid(mesh, cut, occlusal, s.orientation);
}

/// The frame of a tooth for a long axis `occlusal`: mesial-distal along `distal` (made
/// perpendicular), labial completing it away from the arch centre, and the crown centre.
ToothAxes frameAndCrownCentre(const SurfaceMesh& mesh, const Shape& s, const Vec3& occlusal, const Vec3& distal,
                              const Vec3& archCentre, double crownFraction) {
    ToothAxes a;
    a.occlusal = occlusal;
    a.mesialDistal = (distal - distal.dot(occlusal) * occlusal).normalized();
    a.labial = a.occlusal.cross(a.mesialDistal).normalized();
    if (a.labial.dot(s.centroid - archCentre) < 0) a.labial = -a.labial;
    a.crownCentre = crownCentreOf(mesh, s, occlusal, crownFraction);
    return a;
}

/// Radius of the labial face patch that turns tooth unn's long axis (0: none, the anatomical axis).
double labialFaceRadiusOf(int unn, Jaw jaw, const AxesFromShapeOptions& o) {
    if (!isMolar(unn)) return o.labialFaceRadiusMm;
    return jaw == Jaw::Mandible ? o.mandibularMolarLabialFaceRadiusMm : o.molarLabialFaceRadiusMm;
}

/// UNN runs along the arch through the midline (1-16 in the maxilla, 17-32 in the mandible): on the
/// first half of each jaw increasing UNN is mesial, so distal is against it.
bool unnIncreasesMesially(int unn, Jaw jaw) { return unn < (jaw == Jaw::Maxilla ? 8.5 : 24.5); }

/// A lone tooth has no arch: the cross-section's wider principal direction stands in for it.
Vec3 loneToothDirection(const SurfaceMesh& mesh, const Shape& s) {
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Vec3& v : mesh.vertices) cov += (v - s.centroid) * (v - s.centroid).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    return eig.eigenvectors().col(1);
}

/// The frame of tooth unn for long axis `occlusal`: the labial axis perpendicular to it and to the
/// arch direction `along`, away from the arch centre; mesial-distal from the crown's cues
/// (`choice` says which), distal by the tooth's side of the jaw; the crown centre for that axis.
ToothAxes frameForLongAxis(const SurfaceMesh& mesh, const Shape& s, int unn, Jaw jaw, const Vec3& along,
                           const Vec3& archCentre, const Vec3& occlusal, double crownFraction, MesialDistalChoice& choice) {
    Vec3 labial = occlusal.cross(along).normalized();
    if (labial.dot(s.centroid - archCentre) < 0) labial = -labial;
    choice = chooseMesialDistal(mesh, occlusal, along, labial, isMolar(unn));
    const Vec3 distal = unnIncreasesMesially(unn, jaw) ? Vec3(-choice.direction) : choice.direction;
    return frameAndCrownCentre(mesh, s, occlusal, distal, archCentre, crownFraction);
}

/// Arch tangents at the teeth in UNN order (pointing toward increasing UNN), through the crown
/// centres of their anatomical axes; empty for a single tooth.
std::vector<Vec3> archTangentsOf(const std::map<int, SurfaceMesh>& teeth, const std::map<int, Shape>& shapes,
                                 const Vec3& occlusalNormal, double sense, double crownFraction) {
    std::vector<Vec3> centres;
    for (const auto& [unn, s] : shapes) centres.push_back(crownCentreOf(teeth.at(unn), s, sense * s.longAxis, crownFraction));
    return archTangents(centres, occlusalNormal);
}

/// The long axes of the teeth beside `unn` along the arch (the previous and next present UNN),
/// one or two.
std::vector<Vec3> neighbourLongAxes(const std::map<int, ToothAxes>& axes, int unn) {
    std::vector<Vec3> out;
    const auto it = axes.find(unn);
    if (it != axes.begin()) out.push_back(std::prev(it)->second.occlusal);
    if (std::next(it) != axes.end()) out.push_back(std::next(it)->second.occlusal);
    return out;
}

/// Angle, degrees, from tooth unn's long axis to the nearer of its neighbours' (0 without one).
double nearestNeighbourDeg(const std::map<int, ToothAxes>& axes, int unn) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Vec3& n : neighbourLongAxes(axes, unn)) nearest = std::min(nearest, angleDeg(axes.at(unn).occlusal, n));
    return std::isfinite(nearest) ? nearest : 0.0;
}

/// The mean of the neighbours' long axes when they agree with each other within
/// kMaxNeighbourLongAxisDeg; nothing otherwise (a lone tooth, or neighbours that disagree: no
/// better guess).
std::optional<Vec3> agreeingNeighboursMean(const std::map<int, ToothAxes>& axes, int unn) {
    const std::vector<Vec3> around = neighbourLongAxes(axes, unn);
    if (around.empty()) return std::nullopt;
    if (around.size() == 2 && angleDeg(around[0], around[1]) > kMaxNeighbourLongAxisDeg) return std::nullopt;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& n : around) mean += n.normalized();
    return mean.normalized();
}

}  // namespace

double angleDeg(const Vec3& a, const Vec3& b) {
    const double c = a.normalized().dot(b.normalized());
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
}

std::map<int, ToothAxes> toothAxesFromShape(const std::map<int, SurfaceMesh>& teeth, Jaw jaw, const SurfaceMesh& bone,
                                            const AxesFromShapeOptions& o, std::vector<std::string>* notes) {
    std::map<int, Shape> shapes;
    for (const auto& [unn, mesh] : teeth) shapes[unn] = shapeOf(unn, mesh);
    if (shapes.empty()) return {};

    // One occlusal sense for the jaw: first a common line (long axes made to agree), then a vote.
    const Vec3 reference = shapes.begin()->second.longAxis;
    Vec3 common = Vec3::Zero();
    for (auto& [unn, s] : shapes) {
        if (s.longAxis.dot(reference) < 0) s.longAxis = -s.longAxis, s.crownVote = -s.crownVote;
        common += s.longAxis;
    }
    common.normalize();
    double vote = 0;
    bool fromBone = false;
    if (!bone.vertices.empty()) {
        // The bone around a tooth surrounds its root: the tooth centroid lies crown-side of it.
        for (const auto& [unn, s] : shapes) {
            BBox near = s.box;
            near.min.array() -= 1.0;
            near.max.array() += 1.0;
            Vec3 sum = Vec3::Zero();
            std::size_t count = 0;
            for (const Vec3& v : bone.vertices)
                if ((v.array() >= near.min.array()).all() && (v.array() <= near.max.array()).all()) sum += v, ++count;
            if (count > 0) vote += (s.centroid - sum / static_cast<double>(count)).dot(common);
        }
        fromBone = vote != 0;
    }
    if (!fromBone)
        for (const auto& [unn, s] : shapes) vote += s.crownVote;
    if (vote == 0) {
        vote = (jaw == Jaw::Mandible ? 1.0 : -1.0) * common.z();
        if (notes) notes->push_back("tooth axes: occlusal side from the +z convention");
    }
    const double sense = vote >= 0 ? 1.0 : -1.0;

    Vec3 archCentre = Vec3::Zero();
    for (const auto& [unn, s] : shapes) archCentre += s.centroid;
    archCentre /= static_cast<double>(shapes.size());
    const std::vector<Vec3> tangents = archTangentsOf(teeth, shapes, sense * common, sense, o.crownFraction);

    std::map<int, ToothAxes> axes;
    std::vector<Vec3> alongs;  // the arch direction at each tooth, in UNN order
    std::size_t index = 0;
    for (auto it = shapes.begin(); it != shapes.end(); ++it, ++index) {
        const int unn = it->first;
        const Shape& s = it->second;
        const SurfaceMesh& mesh = teeth.at(unn);
        const Vec3 along = tangents.empty() ? loneToothDirection(mesh, s) : tangents[index];
        alongs.push_back(along);
        if (tangents.empty() && notes) notes->push_back("tooth " + std::to_string(unn) + ": no neighbours, mesial-distal and labial senses guessed");
        MesialDistalChoice choice;
        auto frameFor = [&](const Vec3& occlusal) {
            return frameForLongAxis(mesh, s, unn, jaw, along, archCentre, occlusal, o.crownFraction, choice);
        };
        const double faceRadiusMm = labialFaceRadiusOf(unn, jaw, o);
        const Vec3 anatomical = sense * s.longAxis;
        ToothAxes a = frameFor(anatomical);
        // Clinical crown axis: the anatomical axis in the plane of the labial face. The labial face
        // is found from the crown centre, which moves with the axis: two passes settle it.
        bool fromFace = faceRadiusMm > 0;
        for (int pass = 0; pass < 2 && fromFace; ++pass) {
            Vec3 normal;
            // A face tilted more than 30 degrees from the anatomical axis is not a side of the
            // tooth (an incisal edge or an occlusal table the ray happened to leave through).
            if (!labialFaceNormal(mesh, s.orientation, a.crownCentre, a.labial, faceRadiusMm, normal) ||
                std::abs(normal.dot(anatomical)) > 0.5) {
                if (notes) notes->push_back("tooth " + std::to_string(unn) + ": no labial crown face found, long axis = anatomical axis");
                a = frameFor(anatomical);
                fromFace = false;
                break;
            }
            a = frameFor((anatomical - anatomical.dot(normal) * normal).normalized());
        }
        axes[unn] = a;
        if (notes)
            notes->push_back("tooth " + std::to_string(unn) + ": long axis from the " +
                             (fromFace ? "labial face" : "whole tooth") + ", mesial-distal axis from the " + choice.cue +
                             " (" + std::to_string(static_cast<int>(std::lround(choice.offArchDeg))) + " deg from the arch tangent)");
    }
    // A long axis its neighbours contradict is not used: it takes the neighbours' mean (the frame
    // made again around it), and the tooth is reported.
    index = 0;
    for (auto it = shapes.begin(); it != shapes.end(); ++it, ++index) {
        const int unn = it->first;
        const double offDeg = nearestNeighbourDeg(axes, unn);
        if (offDeg <= kMaxNeighbourLongAxisDeg) continue;
        const std::optional<Vec3> mean = agreeingNeighboursMean(axes, unn);
        if (!mean) continue;
        MesialDistalChoice choice;
        axes[unn] = frameForLongAxis(teeth.at(unn), it->second, unn, jaw, alongs[index], archCentre, *mean, o.crownFraction, choice);
        if (notes)
            notes->push_back("tooth " + std::to_string(unn) + ": " + kUncertainAxesNote + ": its long axis from the shape was " +
                             std::to_string(static_cast<int>(std::lround(offDeg))) + " deg from its nearest neighbour's; the mean of its neighbours' taken");
    }
    if (notes && fromBone) notes->push_back("tooth axes: occlusal side from the bone around the roots");
    return axes;
}

}  // namespace jawmesh
