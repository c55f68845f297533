// Insertion of a node on an interface triangle or edge for the sliver improver
// (tet/SliverInterfaceInsert.h).
#include "tet/SliverInterfaceInsert.h"

#include "tet/SliverCavity.h"
#include "tet/SliverSmooth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace jawmesh {
namespace {

struct Candidate {
    Vec3 q;
    std::vector<std::int32_t> holders;    ///< tets whose closure holds q
    std::array<std::int32_t, 3> carrier;  ///< the face (or edge: carrier[2] = -1) q lies on, sorted
};

/// What inserting a candidate would do: the tets it replaces and those it makes (-1 for the new
/// node), and their objective.
struct Insertion {
    Objective objective;
    Vec3 q;
    std::vector<std::int32_t> old;
    std::vector<std::pair<Tet, Label>> fresh;
};

/// Candidates on the faces of t that are not inside t's region.
void addFaceCandidates(const TetMeshEditor& mesh, std::int32_t t, std::vector<Candidate>& candidates) {
    const Tet e = mesh.tet(t);
    for (int k = 0; k < 4; ++k) {
        std::int32_t f[3];
        const std::int32_t other = mesh.acrossFace(t, k, f);
        if (other >= 0 && mesh.label(other) == mesh.label(t)) continue;
        std::vector<std::int32_t> holders{t};
        if (other >= 0) holders.push_back(other);
        std::array<std::int32_t, 3> key{f[0], f[1], f[2]};
        std::sort(key.begin(), key.end());
        const Vec3 &a = mesh.node(f[0]), &b = mesh.node(f[1]), &c = mesh.node(f[2]);
        candidates.push_back({(a + b + c) / 3.0, holders, key});
        // the opposite node's foot on the face, when strictly inside it
        const Vec3 n = (b - a).cross(c - a);
        const double n2 = n.squaredNorm();
        if (!(n2 > 0)) continue;
        const Vec3& apex = mesh.node(e[std::size_t(k)]);
        const Vec3 foot = apex - n * (n.dot(apex - a) / n2);
        const double wa = n.dot((b - foot).cross(c - foot)) / n2, wb = n.dot((c - foot).cross(a - foot)) / n2;
        const double wc = 1.0 - wa - wb;
        if (std::min({wa, wb, wc}) > 0.1) candidates.push_back({wa * a + wb * b + wc * c, holders, key});
    }
}

/// Candidates on the edges of t that are not inside t's region.
void addEdgeCandidates(const TetMeshEditor& mesh, std::int32_t t, std::vector<Candidate>& candidates) {
    const Tet e = mesh.tet(t);
    const auto P = [&](std::int32_t v) -> const Vec3& { return mesh.node(v); };
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            const std::int32_t a = e[std::size_t(i)], b = e[std::size_t(j)];
            if (!mesh.interiorRing(a, b, mesh.label(t)).empty()) continue;  // not on an interface
            const std::vector<std::int32_t> ring = mesh.tetsWith(a, b);
            std::array<std::int32_t, 3> key{std::min(a, b), std::max(a, b), -1};
            candidates.push_back({0.5 * (P(a) + P(b)), ring, key});
            // the point of a-b closest to the opposite edge c-d
            std::int32_t cd[2], n = 0;
            for (auto v : e)
                if (v != a && v != b) cd[n++] = v;
            const Vec3 u = P(b) - P(a), w = P(cd[1]) - P(cd[0]), r = P(a) - P(cd[0]);
            const double uu = u.dot(u), uw = u.dot(w), ww = w.dot(w), ur = u.dot(r), wr = w.dot(r);
            const double den = uu * ww - uw * uw;
            if (!(den > 1e-12 * uu * ww)) continue;
            const double s = (uw * wr - ww * ur) / den;
            if (s > 0.15 && s < 0.85 && std::abs(s - 0.5) > 0.05) candidates.push_back({P(a) + s * u, ring, key});
        }
}

/// The insertion of candidate c: per label around it, its cavity and star (false when a cavity
/// cannot be made star-shaped or its star does not fill it exactly).
bool planInsertion(const TetMeshEditor& mesh, const Candidate& c, double target, Insertion& plan) {
    const bool onFace = c.carrier[2] >= 0;
    const FaceFilter skip = [&](const std::array<std::int32_t, 3>& face) {
        if (onFace) return face == c.carrier;
        return std::binary_search(face.begin(), face.end(), c.carrier[0]) && std::binary_search(face.begin(), face.end(), c.carrier[1]);
    };
    std::vector<Label> labels;
    for (auto h : c.holders) labels.push_back(mesh.label(h));
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    for (Label label : labels) {
        std::vector<std::int32_t> cavity;
        for (auto h : c.holders)
            if (mesh.label(h) == label) cavity.push_back(h);
        growCircumsphereCavity(mesh, cavity, c.q);
        if (!growUntilStarShaped(mesh, cavity, c.q, skip)) return false;
        double volOld = 0, volNew = 0;
        for (auto x : cavity) {
            const Tet& g = mesh.tet(x);
            volOld += signedVolume6(mesh.node(g[0]), mesh.node(g[1]), mesh.node(g[2]), mesh.node(g[3]));
        }
        for (Tet x : starOfCavity(mesh, cavity, skip)) {
            const Vec3* p[4];
            for (int k = 0; k < 4; ++k) p[k] = x[std::size_t(k)] < 0 ? &c.q : &mesh.node(x[std::size_t(k)]);
            const double s6 = sliverScore(*p[0], *p[1], *p[2], *p[3]);
            volNew += signedVolume6(*p[0], *p[1], *p[2], *p[3]);
            plan.objective.add(s6, target);
            plan.fresh.emplace_back(x, label);
        }
        // the star fills exactly the cavity (no face of it missed or counted twice)
        if (std::abs(volNew - volOld) > 1e-9 * volOld) return false;
        plan.old.insert(plan.old.end(), cavity.begin(), cavity.end());
    }
    plan.q = c.q;
    return true;
}

}  // namespace

bool insertOnInterfaceAround(TetMeshEditor& mesh, std::int32_t t, Acceptance& accept, SliverStats& stats) {
    std::vector<Candidate> candidates;
    addFaceCandidates(mesh, t, candidates);
    addEdgeCandidates(mesh, t, candidates);
    Insertion best;
    bool found = false;
    for (const Candidate& c : candidates) {
        Insertion plan;
        if (!planInsertion(mesh, c, accept.target(), plan)) continue;
        if (plan.objective.worst <= kInvalidScore || !accept(plan.objective, objectiveOf(mesh, plan.old, accept.target()))) continue;
        if (!found || plan.objective.betterThan(best.objective)) {
            best = std::move(plan);
            found = true;
        }
    }
    if (!found) return false;
    const std::int32_t m = mesh.addNode(best.q, true);  // on an interface: it never moves
    for (auto x : best.old) mesh.kill(x);
    for (auto& [x, label] : best.fresh) {
        for (auto& v : x)
            if (v < 0) v = m;
        mesh.add(x, label);
    }
    ++stats.interfaceInsertions;
    return true;
}

}  // namespace jawmesh
