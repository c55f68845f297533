// Implements fe/CloseBite.h; what it computes, its rules and its contract are documented there.
#include "fe/CloseBite.h"

#include "filters/RayTriangle.h"
#include "io/Error.h"

#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace jawmesh {
namespace {

constexpr double kCellMm = 1.0;

Jaw jawOfLabel(Label l) { return labelKind(l) == LabelKind::Bone ? (l == boneLabel(Jaw::Mandible) ? Jaw::Mandible : Jaw::Maxilla) : jawOfTooth(labelUnn(l)); }

/// Least distance along `d` from the nodes of `from` to the faces of `to` (+inf: no hit; 0: a node
/// of `from` is inside the region `to` bounds, i.e. a first hit leaves through a face).
double gapAlong(const std::vector<Vec3>& nodes, const std::vector<Tri>& from, const std::vector<Tri>& to, const Vec3& d) {
    const Vec3 u = d.unitOrthogonal(), v = d.cross(u);
    auto cellOf = [&](const Vec3& p) {
        return std::pair<long, long>(static_cast<long>(std::floor(p.dot(u) / kCellMm)), static_cast<long>(std::floor(p.dot(v) / kCellMm)));
    };
    std::map<std::pair<long, long>, std::vector<std::size_t>> bins;
    for (std::size_t f = 0; f < to.size(); ++f) {
        std::pair<long, long> lo(std::numeric_limits<long>::max(), std::numeric_limits<long>::max()), hi(std::numeric_limits<long>::min(), std::numeric_limits<long>::min());
        for (std::int32_t n : to[f]) {
            const auto c = cellOf(nodes[static_cast<std::size_t>(n)]);
            lo = {std::min(lo.first, c.first), std::min(lo.second, c.second)};
            hi = {std::max(hi.first, c.first), std::max(hi.second, c.second)};
        }
        for (long i = lo.first; i <= hi.first; ++i)
            for (long j = lo.second; j <= hi.second; ++j) bins[{i, j}].push_back(f);
    }
    std::set<std::int32_t> sources;
    for (const Tri& t : from) sources.insert(t.begin(), t.end());
    double gap = std::numeric_limits<double>::infinity();
    for (std::int32_t s : sources) {
        const Vec3& p = nodes[static_cast<std::size_t>(s)];
        const auto bin = bins.find(cellOf(p));
        if (bin == bins.end()) continue;
        // First hit each way: a node inside the other crown leaves it through its exposed surface
        // (its crown top is attached to the root, so only one way may show it).
        double ahead = std::numeric_limits<double>::infinity(), behind = ahead;
        bool leavesAhead = false, leavesBehind = false;
        for (std::size_t f : bin->second) {
            const Vec3& a = nodes[static_cast<std::size_t>(to[f][0])];
            const Vec3& b = nodes[static_cast<std::size_t>(to[f][1])];
            const Vec3& c = nodes[static_cast<std::size_t>(to[f][2])];
            const double facing = (b - a).cross(c - a).dot(d);  // > 0: the outward normal points along d
            const double t = rayTriangleHit(p, d, a, b, c), back = rayTriangleHit(p, -d, a, b, c);
            if (t < ahead) ahead = t, leavesAhead = facing > 0;
            if (back < behind) behind = back, leavesBehind = facing < 0;
        }
        if ((std::isfinite(ahead) && leavesAhead) || (std::isfinite(behind) && leavesBehind)) return 0.0;
        gap = std::min(gap, ahead);
    }
    return gap;
}

}  // namespace

double biteGapMm(const TetMesh& mesh, const std::vector<ExteriorFace>& exterior, const Vec3& up) {
    std::vector<Tri> lower, upper;
    for (const ExteriorFace& f : exterior)
        if (isToothLike(labelKind(f.label))) (jawOfTooth(labelUnn(f.label)) == Jaw::Mandible ? lower : upper).push_back(f.nodes);
    const Vec3 d = up.normalized();
    return std::min(gapAlong(mesh.nodes, lower, upper, d), gapAlong(mesh.nodes, upper, lower, -d));
}

TetMesh withMandibleMoved(const TetMesh& mesh, const Vec3& offsetMm) {
    std::vector<signed char> jawOfNode(mesh.nodes.size(), -1);  // -1 none, 0 mandible, 1 maxilla
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const signed char jaw = jawOfLabel(mesh.labels[t]) == Jaw::Mandible ? 0 : 1;
        for (std::int32_t n : mesh.tets[t]) {
            signed char& j = jawOfNode[static_cast<std::size_t>(n)];
            if (j >= 0 && j != jaw) throw Error("node " + std::to_string(n + 1) + " belongs to both jaws: mesh the jaws apart to close the bite");
            j = jaw;
        }
    }
    TetMesh moved = mesh;
    for (std::size_t n = 0; n < moved.nodes.size(); ++n)
        if (jawOfNode[n] == 0) moved.nodes[n] += offsetMm;
    return moved;
}

}  // namespace jawmesh
