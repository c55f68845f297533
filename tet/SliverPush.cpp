// The bounded push of an interface node off a thin spot (tet/SliverPush.h).
#include "tet/SliverPush.h"

#include "filters/SelfIntersections.h"
#include "tet/SliverSmooth.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>
#include <vector>

namespace jawmesh {
namespace {

/// Whether the outer faces around node v (its star's faces with no tet across), with v at p, meet
/// another outer face (exact test; faces that share a node are tested too, trianglesIntersect
/// knows what they share). One scan of outerFaces for those whose boxes reach theirs.
bool outerFacesMeet(const TetMeshEditor& mesh, const std::vector<Tri>& outerFaces, std::int32_t v, const Vec3& p) {
    const auto at = [&](std::int32_t w) -> const Vec3& { return w == v ? p : mesh.node(w); };
    std::vector<Tri> around;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const std::int32_t t : mesh.star(v))
        for (int k = 0; k < 4; ++k) {
            std::int32_t f[3];
            if (mesh.tet(t)[std::size_t(k)] == v || mesh.acrossFace(t, k, f) >= 0) continue;
            around.push_back({f[0], f[1], f[2]});
            for (const std::int32_t w : f) {
                lo = lo.cwiseMin(at(w));
                hi = hi.cwiseMax(at(w));
            }
        }
    const auto sorted = [](Tri f) {
        std::sort(f.begin(), f.end());
        return f;
    };
    for (const Tri& b : outerFaces) {
        const Vec3 pb[3] = {at(b[0]), at(b[1]), at(b[2])};
        const Vec3 blo = pb[0].cwiseMin(pb[1]).cwiseMin(pb[2]), bhi = pb[0].cwiseMax(pb[1]).cwiseMax(pb[2]);
        if ((blo.array() > hi.array()).any() || (bhi.array() < lo.array()).any()) continue;
        for (const Tri& a : around) {
            if (sorted(a) == sorted(b)) continue;
            const Vec3 pa[3] = {at(a[0]), at(a[1]), at(a[2])};
            if (trianglesIntersect(pa, a, pb, b)) return true;
        }
    }
    return false;
}

}  // namespace

std::vector<Tri> outerBoundaryFaces(const TetMeshEditor& mesh) {
    std::vector<Tri> faces;
    for (std::size_t t = 0; t < mesh.tetCount(); ++t) {
        if (!mesh.alive(std::int32_t(t))) continue;
        for (int k = 0; k < 4; ++k) {
            std::int32_t f[3];
            if (mesh.acrossFace(std::int32_t(t), k, f) < 0) faces.push_back({f[0], f[1], f[2]});
        }
    }
    return faces;
}

bool pushInterfaceNode(TetMeshEditor& mesh, std::int32_t t, double maxMm, Acceptance& accept, InterfacePushes& pushes,
                       SliverStats& stats, const std::vector<Tri>* outerFaces) {
    if (!mesh.alive(t) || mesh.score(t) >= accept.target()) return false;
    const Tet e = mesh.tet(t);
    const auto P = [&](std::int32_t v) -> const Vec3& { return mesh.node(v); };
    std::array<std::pair<double, int>, 4> order;
    std::array<Vec3, 4> away;
    for (int k = 0; k < 4; ++k) {
        const Vec3 &a = P(e[std::size_t((k + 1) % 4)]), &b = P(e[std::size_t((k + 2) % 4)]), &c = P(e[std::size_t((k + 3) % 4)]);
        Vec3 n = (b - a).cross(c - a).normalized();
        if (n.dot(P(e[std::size_t(k)]) - a) < 0) n = -n;
        away[std::size_t(k)] = n;
        order[std::size_t(k)] = {n.dot(P(e[std::size_t(k)]) - a), k};
    }
    std::sort(order.begin(), order.end());
    for (const auto& [height, k] : order) {
        const std::int32_t v = e[std::size_t(k)];
        if (!mesh.fixed(v) || pushes.pushed.count(v) || mesh.onMeshBoundary(v) != (outerFaces != nullptr)) continue;
        std::vector<Tet> tets;
        for (auto s : mesh.star(v)) tets.push_back(mesh.tet(s));
        Objective best = objectiveWith(mesh.nodes(), tets, v, P(v), accept.target());
        double bestStep = 0;
        for (int i = 1; i <= 8; ++i) {
            const double step = maxMm * i / 8.0;
            const Vec3 to = P(v) + step * away[std::size_t(k)];
            const Objective o = objectiveWith(mesh.nodes(), tets, v, to, accept.target());
            if (accept(o, best) && !(outerFaces && outerFacesMeet(mesh, *outerFaces, v, to))) {
                best = o;
                bestStep = step;
            }
        }
        if (bestStep == 0) continue;
        for (auto s : mesh.star(v)) pushes.volumeChange[mesh.label(s)] -= mesh.volume(s);
        mesh.move(v, P(v) + bestStep * away[std::size_t(k)]);
        for (auto s : mesh.star(v)) pushes.volumeChange[mesh.label(s)] += mesh.volume(s);
        pushes.pushed.insert(v);
        ++stats.interfacePushes;
        if (outerFaces) ++stats.outerPushes;
        stats.largestPushMm = std::max(stats.largestPushMm, bestStep);
        return true;
    }
    return false;
}

}  // namespace jawmesh
