// Implements the test helpers of support_SyntheticLabels.h (documented there).
#include "support_SyntheticLabels.h"

#include "io/PolyWriter.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace jawmesh::test {

double SyntheticField::sdf(Label label, const Vec3& p) const {
    if (label != kOutsideLabel) {
        double earlier = -1e9;  // max over earlier regions of -sdf: they win where they overlap
        for (const auto& r : regions) {
            if (r.label == label) return std::max(r.sdf(p), earlier);
            earlier = std::max(earlier, -r.sdf(p));
        }
        return 1e9;
    }
    double m = 1e9;
    for (const auto& r : regions) m = std::min(m, r.sdf(p));
    return -m;
}

Label SyntheticField::labelAt(const Vec3& p) const {
    for (const auto& r : regions)
        if (r.sdf(p) < 0.0) return r.label;
    return kOutsideLabel;
}

SyntheticField sampleField(const std::vector<AnalyticRegion>& regions, const Vec3& lo, const Vec3& hi,
                           double voxel) {
    SyntheticField s;
    s.regions = regions;
    s.field.voxelSizeMm = voxel;
    const auto xform = openvdb::math::Transform::createLinearTransform(voxel);
    s.field.labels = openvdb::Int32Grid::create(kOutsideLabel);
    s.field.labels->setTransform(xform);
    const float band = float(3.0 * voxel);
    for (const auto& r : regions) {
        auto g = openvdb::FloatGrid::create(band);
        g->setTransform(xform);
        g->setGridClass(openvdb::GRID_LEVEL_SET);
        s.field.distances[r.label] = g;
    }
    const openvdb::Coord cmin(int(std::floor(lo.x() / voxel)) - 4, int(std::floor(lo.y() / voxel)) - 4,
                              int(std::floor(lo.z() / voxel)) - 4);
    const openvdb::Coord cmax(int(std::ceil(hi.x() / voxel)) + 4, int(std::ceil(hi.y() / voxel)) + 4,
                              int(std::ceil(hi.z() / voxel)) + 4);
    auto lacc = s.field.labels->getAccessor();
    std::vector<openvdb::FloatGrid::Accessor> dacc;
    for (const auto& r : regions) dacc.push_back(s.field.distances[r.label]->getAccessor());
    for (int i = cmin.x(); i <= cmax.x(); ++i)
        for (int j = cmin.y(); j <= cmax.y(); ++j)
            for (int k = cmin.z(); k <= cmax.z(); ++k) {
                const Vec3 p(i * voxel, j * voxel, k * voxel);
                const openvdb::Coord c(i, j, k);
                const Label L = s.labelAt(p);  // first region with sdf < 0 wins
                if (L != kOutsideLabel) lacc.setValue(c, L);
                for (std::size_t r = 0; r < regions.size(); ++r) {
                    // a region's own distance, restricted to where earlier regions do not win
                    double d = regions[r].sdf(p);
                    for (std::size_t q = 0; q < r; ++q) d = std::max(d, -regions[q].sdf(p));
                    const float f = float(std::clamp(d, -double(band), double(band)));
                    if (std::abs(d) < band) dacc[r].setValue(c, f);
                    else if (d < 0.0) dacc[r].setValueOff(c, -band);
                }
            }
    return s;
}

namespace {
double capsule(const Vec3& p, const Vec3& a, const Vec3& b, double r) {
    const Vec3 ab = b - a;
    const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (p - (a + t * ab)).norm() - r;
}
double box(const Vec3& p, const Vec3& lo, const Vec3& hi) {
    const Vec3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    const Vec3 q = (p - c).cwiseAbs() - h;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}
}  // namespace

SyntheticField jawPhantom(double voxel) {
    const Vec3 boxLo(0.0, 0.0, -1.6), boxHi(3.0, 2.0, 0.0);
    const double r = 0.45, pdl = 0.2;
    const Vec3 a1(0.85, 1.0, -0.9), b1(0.85, 1.0, 0.6);
    const Vec3 a2(2.15, 1.0, -0.8), b2(2.15, 1.0, 0.55);
    std::vector<AnalyticRegion> regions;
    regions.push_back({toothLabel(24), [=](const Vec3& p) { return capsule(p, a1, b1, r); }});
    regions.push_back({toothLabel(25), [=](const Vec3& p) { return capsule(p, a2, b2, r); }});
    regions.push_back({pdlLabel(24), [=](const Vec3& p) {
                           return std::max(capsule(p, a1, b1, r + pdl), box(p, boxLo, boxHi));
                       }});
    regions.push_back({pdlLabel(25), [=](const Vec3& p) {
                           return std::max(capsule(p, a2, b2, r + pdl), box(p, boxLo, boxHi));
                       }});
    regions.push_back({kMandibleBoneLabel, [=](const Vec3& p) { return box(p, boxLo, boxHi); }});
    return sampleField(regions, Vec3(0.0, 0.0, -1.6), Vec3(3.0, 2.0, 1.1), voxel);
}

LabelField rawField(const std::vector<Label>& labels, int nx, int ny, int nz, double voxel) {
    LabelField f;
    f.voxelSizeMm = voxel;
    f.labels = openvdb::Int32Grid::create(kOutsideLabel);
    f.labels->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    auto acc = f.labels->getAccessor();
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const Label L = labels[std::size_t(i + nx * (j + ny * k))];
                if (L != kOutsideLabel) acc.setValue(openvdb::Coord(i, j, k), L);
            }
    return f;
}

Label voxelLabelAt(const LabelField& field, const Vec3& p) {
    const auto ijk = field.labels->transform().worldToIndexNodeCentered(openvdb::Vec3d(p.x(), p.y(), p.z()));
    return field.labels->tree().getValue(ijk);
}

std::string checkRegionBoundary(const InterfaceComplex& complex, Label label) {
    const SurfaceMesh b = regionBoundary(complex, label);
    std::map<std::pair<int, int>, int> directed;
    for (const Tri& t : b.triangles)
        for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    for (const auto& [e, n] : directed) {
        if (n != 1) return labelName(label) + ": directed edge used " + std::to_string(n) + " times";
        const auto it = directed.find({e.second, e.first});
        if (it == directed.end()) return labelName(label) + ": boundary edge (not closed)";
    }
    // vertex manifold: the triangles around each vertex form one cycle
    std::vector<std::map<int, int>> next(b.vertices.size());  // around v: from corner -> to corner
    for (const Tri& t : b.triangles)
        for (int k = 0; k < 3; ++k) next[t[k]][t[(k + 1) % 3]] = t[(k + 2) % 3];
    for (std::size_t v = 0; v < b.vertices.size(); ++v) {
        if (next[v].empty()) continue;
        int start = next[v].begin()->first, cur = start;
        std::size_t steps = 0;
        do {
            cur = next[v].at(cur);
            ++steps;
        } while (cur != start && steps <= next[v].size());
        if (steps != next[v].size())
            return labelName(label) + ": non-manifold vertex " + std::to_string(v);
    }
    return {};
}

std::pair<long, int> eulerAndComponents(const SurfaceMesh& m) {
    std::vector<std::uint64_t> edges;
    edges.reserve(3 * m.triangles.size());
    std::vector<std::int32_t> parent(m.vertices.size(), -1);  // -1: unused
    const auto find = [&](std::int32_t x) {
        while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
        return x;
    };
    for (const Tri& t : m.triangles)
        for (auto v : t)
            if (parent[std::size_t(v)] < 0) parent[std::size_t(v)] = v;
    for (const Tri& t : m.triangles)
        for (int k = 0; k < 3; ++k) {
            const std::uint64_t a = std::uint32_t(std::min(t[k], t[(k + 1) % 3])), b = std::uint32_t(std::max(t[k], t[(k + 1) % 3]));
            edges.push_back(a << 32 | b);
            const auto ra = find(t[k]), rb = find(t[(k + 1) % 3]);
            if (ra != rb) parent[std::size_t(std::max(ra, rb))] = std::min(ra, rb);
        }
    std::sort(edges.begin(), edges.end());
    const long nEdges = long(std::unique(edges.begin(), edges.end()) - edges.begin());
    long nVerts = 0;
    int components = 0;
    for (std::size_t v = 0; v < parent.size(); ++v) {
        if (parent[v] < 0) continue;
        ++nVerts;
        components += find(std::int32_t(v)) == std::int32_t(v);
    }
    return {nVerts - nEdges + long(m.triangles.size()), components};
}

double windingNumber(const SurfaceMesh& mesh, const Vec3& p) {
    double sum = 0.0;
    for (const Tri& t : mesh.triangles) {
        const Vec3 a = mesh.vertices[t[0]] - p, b = mesh.vertices[t[1]] - p, c = mesh.vertices[t[2]] - p;
        const double la = a.norm(), lb = b.norm(), lc = c.norm();
        const double num = a.dot(b.cross(c));
        const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        sum += 2.0 * std::atan2(num, den);
    }
    return sum / (4.0 * M_PI);
}

std::set<Label> regionLabels(const InterfaceComplex& complex) {
    std::set<Label> s;
    for (const auto& p : complex.sides) s.insert(p.begin(), p.end());
    s.erase(kOutsideLabel);
    return s;
}

}  // namespace jawmesh::test
