// Implements io/ArchNumbering.h; what it computes, its rules and its contract are documented there.
#include "io/ArchNumbering.h"

#include "io/Angles.h"
#include "io/Error.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

namespace jawmesh {
namespace {

struct UnionFind {
    std::vector<std::int32_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    std::int32_t find(std::int32_t a) {
        while (parent[static_cast<std::size_t>(a)] != a) {
            parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
            a = parent[static_cast<std::size_t>(a)];
        }
        return a;
    }
    void unite(std::int32_t a, std::int32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
};

/// Triangle lists of the connected components (vertices at equal positions count as shared),
/// ordered by their first triangle.
std::vector<std::vector<std::size_t>> components(const SurfaceMesh& mesh) {
    const std::size_t nv = mesh.vertices.size();
    UnionFind uf(nv);
    std::vector<std::int32_t> order(nv);
    std::iota(order.begin(), order.end(), 0);
    auto less = [&](std::int32_t a, std::int32_t b) {
        const Vec3& p = mesh.vertices[static_cast<std::size_t>(a)];
        const Vec3& q = mesh.vertices[static_cast<std::size_t>(b)];
        return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t i = 1; i < nv; ++i)
        if (!less(order[i - 1], order[i])) uf.unite(order[i - 1], order[i]);
    for (const Tri& t : mesh.triangles) {
        uf.unite(t[0], t[1]);
        uf.unite(t[0], t[2]);
    }
    std::map<std::int32_t, std::size_t> index;
    std::vector<std::vector<std::size_t>> result;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto [it, inserted] = index.emplace(uf.find(mesh.triangles[t][0]), result.size());
        if (inserted) result.emplace_back();
        result[it->second].push_back(t);
    }
    return result;
}

SurfaceMesh extract(const SurfaceMesh& mesh, const std::vector<std::size_t>& triangles) {
    SurfaceMesh out;
    std::map<std::int32_t, std::int32_t> remap;
    for (std::size_t t : triangles) {
        Tri tri;
        for (std::size_t j = 0; j < 3; ++j) {
            const std::int32_t v = mesh.triangles[t][j];
            const auto [it, inserted] = remap.emplace(v, static_cast<std::int32_t>(out.vertices.size()));
            if (inserted) out.vertices.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
            tri[j] = it->second;
        }
        out.triangles.push_back(tri);
    }
    return out;
}

Vec3 areaCentroid(const SurfaceMesh& mesh) {
    Vec3 sum = Vec3::Zero();
    double area = 0;
    for (const Tri& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        const double w = 0.5 * (b - a).cross(c - a).norm();
        sum += w * (a + b + c) / 3.0;
        area += w;
    }
    if (area > 0) return sum / area;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& v : mesh.vertices) mean += v;
    return mean / static_cast<double>(std::max<std::size_t>(1, mesh.vertices.size()));
}

bool contains(const BBox& outer, const BBox& inner) {
    return (outer.min.array() <= inner.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
}

/// The teeth of the combined mesh: its components, shells nested in another component's box
/// (pulp cavities) joined to it, specks (box diagonal under 20% of the median's) dropped.
struct ToothParts {
    std::vector<SurfaceMesh> teeth;
    std::vector<BBox> boxes;
    std::size_t joined = 0, dropped = 0;
};

ToothParts toothParts(const SurfaceMesh& allTeeth) {
    std::vector<std::vector<std::size_t>> parts = components(allTeeth);
    if (parts.empty()) throw Error("all_teeth: no triangles to split into teeth");
    std::vector<BBox> boxes(parts.size());
    for (std::size_t i = 0; i < parts.size(); ++i)
        for (std::size_t t : parts[i])
            for (std::int32_t v : allTeeth.triangles[t]) boxes[i].extend(allTeeth.vertices[static_cast<std::size_t>(v)]);
    std::vector<double> diagonals;
    for (const BBox& b : boxes) diagonals.push_back(b.size().norm());
    std::nth_element(diagonals.begin(), diagonals.begin() + static_cast<std::ptrdiff_t>(diagonals.size() / 2), diagonals.end());
    const double medianDiagonal = diagonals[diagonals.size() / 2];
    std::vector<std::size_t> container(parts.size(), parts.size());  // largest box holding part i
    for (std::size_t i = 0; i < parts.size(); ++i)
        for (std::size_t j = 0; j < parts.size(); ++j) {
            const bool holds = j != i && contains(boxes[j], boxes[i]) && !(contains(boxes[i], boxes[j]) && j > i);
            if (holds && (container[i] == parts.size() || boxes[j].size().prod() > boxes[container[i]].size().prod()))
                container[i] = j;
        }
    auto root = [&](std::size_t i) {
        for (std::size_t steps = 0; container[i] != parts.size() && steps < parts.size(); ++steps) i = container[i];
        return i;
    };
    ToothParts out;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        if (container[i] != parts.size()) continue;
        if (boxes[i].size().norm() < 0.2 * medianDiagonal) {
            ++out.dropped;
            continue;
        }
        std::vector<std::size_t> tris = parts[i];
        for (std::size_t j = 0; j < parts.size(); ++j)
            if (j != i && container[j] != parts.size() && root(j) == i) {
                tris.insert(tris.end(), parts[j].begin(), parts[j].end());
                ++out.joined;
            }
        std::sort(tris.begin(), tris.end());
        out.teeth.push_back(extract(allTeeth, tris));
        out.boxes.push_back(boxes[i]);
    }
    if (out.teeth.empty()) throw Error("all_teeth: no component large enough to be a tooth");
    return out;
}

/// The occlusal direction: normal of the least-squares plane of the centroids, on the side where
/// the crowns stick out of the bone (fromBone), else +z for a mandible and -z for a maxilla.
Vec3 occlusalDirection(const std::vector<Vec3>& centroids, const Vec3& mean, const std::vector<BBox>& boxes,
                       const SurfaceMesh& bone, Jaw jaw, bool& fromBone) {
    const std::size_t n = centroids.size();
    Vec3 normal = Vec3::UnitZ();
    if (n >= 3) {
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (const Vec3& c : centroids) cov += (c - mean) * (c - mean).transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
        normal = eig.eigenvectors().col(0).normalized();
        if (normal.z() < 0) normal = -normal;
    }
    double vote = 0;
    for (std::size_t i = 0; i < n; ++i) {
        BBox near = boxes[i];
        near.min.array() -= 1.0;
        near.max.array() += 1.0;
        Vec3 sum = Vec3::Zero();
        std::size_t count = 0;
        for (const Vec3& v : bone.vertices)
            if ((v.array() >= near.min.array()).all() && (v.array() <= near.max.array()).all()) {
                sum += v;
                ++count;
            }
        if (count > 0) vote += (centroids[i] - sum / static_cast<double>(count)).dot(normal);
    }
    fromBone = vote != 0;
    return fromBone ? (vote > 0 ? normal : Vec3(-normal)) : (jaw == Jaw::Mandible ? normal : Vec3(-normal));
}

/// Teeth in order along the arch from the patient's left end: by angle around the mean centroid,
/// starting after the largest gap; `anterior` gets the in-plane direction to the front.
std::vector<std::size_t> orderAlongArch(const std::vector<Vec3>& centroids, const Vec3& mean, const Vec3& superior, Vec3& anterior) {
    const std::size_t n = centroids.size();
    const Vec3 e1 = (std::abs(superior.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(superior).normalized();
    const Vec3 e2 = superior.cross(e1);
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::vector<double> angle(n);
    for (std::size_t i = 0; i < n; ++i) angle[i] = std::atan2((centroids[i] - mean).dot(e2), (centroids[i] - mean).dot(e1));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return angle[a] < angle[b]; });
    std::size_t start = 0;
    double widest = -1;
    for (std::size_t k = 0; k < n; ++k) {
        const double prev = angle[order[(k + n - 1) % n]];
        double gap = angle[order[k]] - prev;
        if (gap <= 0) gap += 2 * kPi;
        if (gap > widest) {
            widest = gap;
            start = k;
        }
    }
    std::rotate(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(start), order.end());
    anterior = -Vec3::UnitY();
    if (n >= 3) {
        const Vec3 d = mean - 0.5 * (centroids[order.front()] + centroids[order.back()]);
        const Vec3 inPlane = d - d.dot(superior) * superior;
        if (inPlane.norm() > 1e-9) anterior = inPlane.normalized();
    }
    const Vec3 left = superior.cross(anterior);
    if (n >= 2 && (centroids[order.front()] - centroids[order.back()]).dot(left) < 0) std::reverse(order.begin(), order.end());
    return order;
}

/// How many of the ordered teeth lie on the patient's left of the midline: the midline runs
/// between the adjacent pair whose midpoint is most anterior.
std::size_t teethLeftOfMidline(const std::vector<Vec3>& centroids, const std::vector<std::size_t>& order, const Vec3& mean,
                               const Vec3& anterior, const Vec3& left) {
    const std::size_t n = order.size();
    if (n < 2) return (centroids[0] - mean).dot(left) < 0 ? 0 : 1;  // a single tooth: its side
    std::size_t lastLeft = 0;
    double best = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const double a = (0.5 * (centroids[order[k]] + centroids[order[k + 1]])).dot(anterior);
        if (a > best) {
            best = a;
            lastLeft = k;
        }
    }
    return lastLeft + 1;
}

}  // namespace

std::map<int, SurfaceMesh> numberTeethAlongArch(const SurfaceMesh& allTeeth, Jaw jaw, const SurfaceMesh& bone,
                                                std::vector<std::string>* notes) {
    ToothParts parts = toothParts(allTeeth);
    const std::size_t n = parts.teeth.size();
    std::vector<Vec3> centroids;
    for (const SurfaceMesh& tooth : parts.teeth) centroids.push_back(areaCentroid(tooth));
    Vec3 mean = Vec3::Zero();
    for (const Vec3& c : centroids) mean += c;
    mean /= static_cast<double>(n);
    bool fromBone = false;
    const Vec3 occlusal = occlusalDirection(centroids, mean, parts.boxes, bone, jaw, fromBone);
    const Vec3 superior = jaw == Jaw::Mandible ? occlusal : Vec3(-occlusal);
    Vec3 anterior;
    const std::vector<std::size_t> order = orderAlongArch(centroids, mean, superior, anterior);
    const std::size_t leftCount = teethLeftOfMidline(centroids, order, mean, anterior, superior.cross(anterior));
    const std::size_t rightCount = n - leftCount;
    if (leftCount > 8 || rightCount > 8)
        throw Error("all_teeth: " + std::to_string(leftCount) + " teeth on the patient's left and " +
                    std::to_string(rightCount) + " on the right; at most 8 per side can be numbered");
    const int leftCentral = jaw == Jaw::Mandible ? 24 : 9, leftStep = jaw == Jaw::Mandible ? -1 : 1;
    const int rightCentral = jaw == Jaw::Mandible ? 25 : 8, rightStep = jaw == Jaw::Mandible ? 1 : -1;

    std::map<int, SurfaceMesh> result;
    std::ostringstream note;
    note << "all_teeth: " << n << " teeth numbered along the arch (patient left to right):";
    for (std::size_t k = 0; k < n; ++k) {
        const int unn = k < leftCount ? leftCentral + leftStep * static_cast<int>(leftCount - 1 - k)
                                      : rightCentral + rightStep * static_cast<int>(k - leftCount);
        note << ' ' << unn;
        result.emplace(unn, std::move(parts.teeth[order[k]]));
    }
    note << "; occlusal side from " << (fromBone ? "the bone around the roots" : "the +z convention");
    if (parts.joined) note << "; " << parts.joined << " nested shell(s) joined to their tooth";
    if (parts.dropped) note << "; " << parts.dropped << " tiny component(s) dropped";
    if (notes) notes->push_back(note.str());
    return result;
}

}  // namespace jawmesh
