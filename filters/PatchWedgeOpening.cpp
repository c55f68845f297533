// Implements filters/PatchWedgeOpening.h; what it computes, its rules and its contract are documented there.
#include "filters/PatchWedgeOpening.h"

#include "filters/PatchChecks.h"
#include "filters/PatchWedge.h"

#include <algorithm>
#include <array>

namespace jawmesh {
namespace {

/// The triangles other than t whose boxes meet t's box grown by `margin` mm.
std::vector<std::int32_t> trianglesNear(const SurfaceMesh& s, std::size_t t, double margin) {
    BBox box = triangleBox(s, s.triangles[t]);
    box.min.array() -= margin;
    box.max.array() += margin;
    return trianglesMeeting(s, box, [t](std::size_t u) { return u == t; });
}

/// The triangles at each vertex, kept up to date as flips and bumps change the complex: a repair
/// triangle's wedges need only the triangles that share an edge with it, and scanning the whole
/// surface for them made a patch of a few thousand triangles take a minute.
struct TrianglesAt {
    std::vector<std::vector<std::int32_t>> of;  ///< per vertex
    explicit TrianglesAt(const SurfaceMesh& s) : of(s.vertices.size()) {
        for (std::size_t t = 0; t < s.triangles.size(); ++t) add(s.triangles[t], t);
    }
    void add(const Tri& f, std::size_t t) {
        for (const std::int32_t v : f) {
            if (std::size_t(v) >= of.size()) of.resize(std::size_t(v) + 1);
            of[std::size_t(v)].push_back(std::int32_t(t));
        }
    }
    void remove(const Tri& f, std::size_t t) {
        for (const std::int32_t v : f) {
            auto& list = of[std::size_t(v)];
            list.erase(std::find(list.begin(), list.end(), std::int32_t(t)));
        }
    }
    /// The triangles that share a vertex with any of `tris` (every triangle sharing an edge with
    /// one among them), but those listed in `skip`, in index order.
    std::vector<std::int32_t> touching(const std::vector<Tri>& tris, const std::vector<std::size_t>& skip) const {
        std::vector<std::int32_t> out;
        for (const Tri& f : tris)
            for (const std::int32_t v : f) out.insert(out.end(), of[std::size_t(v)].begin(), of[std::size_t(v)].end());
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        out.erase(std::remove_if(out.begin(), out.end(),
                                 [&](std::int32_t u) { return std::count(skip.begin(), skip.end(), std::size_t(u)) > 0; }),
                  out.end());
        return out;
    }
};

/// The smallest wedge over triangle t's edges.
double wedgeOf(const InterfaceComplex& c, std::size_t t, const TrianglesAt& at) {
    return patchSmallestWedgeDeg(c, at.touching({c.surface.triangles[t]}, {t}), {c.surface.triangles[t]}, {}, c.sides[t]);
}

/// Bumps triangle t when that opens its smallest wedge (under minWedgeDeg); true when it did.
bool bump(InterfaceComplex& c, std::vector<char>& repair, TrianglesAt& at, std::size_t t, double minWedgeDeg) {
    SurfaceMesh& s = c.surface;
    const Tri tri = s.triangles[t];
    double bestDeg = wedgeOf(c, t, at);
    if (bestDeg >= minWedgeDeg) return false;
    const Vec3 &a = s.vertices[std::size_t(tri[0])], &b = s.vertices[std::size_t(tri[1])], &d = s.vertices[std::size_t(tri[2])];
    const double longest = std::max({(b - a).norm(), (d - b).norm(), (a - d).norm()});
    const std::vector<std::int32_t> near = trianglesNear(s, t, longest);  // the highest lift
    const Vec3 normal = (b - a).cross(d - a).normalized(), centroid = (a + b + d) / 3.0;
    const auto p = std::int32_t(s.vertices.size());
    const std::vector<Tri> fan = {{tri[0], tri[1], p}, {tri[1], tri[2], p}, {tri[2], tri[0], p}};
    const std::vector<std::int32_t> rim(tri.begin(), tri.end());
    Vec3 best;
    bool found = false;
    for (const double f : {0.0625, -0.0625, 0.125, -0.125, 0.25, -0.25, 0.5, -0.5, 1.0, -1.0}) {
        const std::vector<Vec3> apex = {centroid + f * longest * normal};
        const double deg = patchSmallestWedgeDeg(c, near, fan, apex, c.sides[t]);
        if (deg <= bestDeg || !patchIsClean(s, fan, apex, near) || patchSweepsAVertex(s, near, rim, {tri}, {}, fan, apex, c.seeds)) continue;
        best = apex.front();
        bestDeg = deg;
        found = true;
    }
    if (!found) return false;
    s.vertices.push_back(best);
    at.remove(tri, t);
    s.triangles[t] = fan[0];
    at.add(fan[0], t);
    for (std::size_t k = 1; k < 3; ++k) {
        at.add(fan[k], s.triangles.size());
        s.triangles.push_back(fan[k]);
        c.sides.push_back(c.sides[t]);
        repair.push_back(1);
    }
    return true;
}

/// The triangle other than t on edge a-b when exactly two share it, else -1.
std::int32_t onlyOtherOn(const std::vector<std::int32_t>& near, const SurfaceMesh& s, std::int32_t a, std::int32_t b) {
    std::int32_t other = -1;
    for (const std::int32_t u : near) {
        const Tri& f = s.triangles[std::size_t(u)];
        if (std::count(f.begin(), f.end(), a) && std::count(f.begin(), f.end(), b)) {
            if (other >= 0) return -1;
            other = u;
        }
    }
    return other;
}

/// Flips the edge from corner k of triangle t when that opens the smallest wedge of the five edges
/// it changes (under minWedgeDeg); true when it did.
bool flip(InterfaceComplex& c, const std::vector<char>& repair, TrianglesAt& at, std::size_t t, std::size_t k, double minWedgeDeg) {
    SurfaceMesh& s = c.surface;
    const Tri t1 = s.triangles[t];
    const std::int32_t a = t1[k], b = t1[(k + 1) % 3], cv = t1[(k + 2) % 3];
    const std::int32_t u = onlyOtherOn(at.touching({t1}, {t}), s, a, b);
    if (u < 0 || !repair[std::size_t(u)]) return false;
    // A triangle with the sides the other way round and the opposite winding is the same face.
    Tri t2 = s.triangles[std::size_t(u)];
    const std::array<Label, 2> sides = c.sides[t], reversed = {sides[1], sides[0]};
    if (c.sides[std::size_t(u)] == reversed) std::swap(t2[1], t2[2]);
    else if (c.sides[std::size_t(u)] != sides) return false;
    std::size_t ib = 0;
    while (t2[ib] != b) ++ib;
    if (t2[(ib + 1) % 3] != a) return false;  // not wound consistently
    const std::int32_t d = t2[(ib + 2) % 3];
    if (d == cv) return false;
    const std::vector<Tri> before = {t1, t2}, after = {{a, d, cv}, {d, b, cv}};
    const double beforeDeg = patchSmallestWedgeDeg(c, at.touching(before, {t, std::size_t(u)}), before, {}, sides);
    if (beforeDeg >= minWedgeDeg) return false;
    // Every triangle the quad's box meets: d lies within |d - a| of t.
    std::vector<std::int32_t> near = trianglesNear(s, t, (s.vertices[std::size_t(d)] - s.vertices[std::size_t(a)]).norm());
    near.erase(std::find(near.begin(), near.end(), u));
    for (const std::int32_t w : near) {  // the new edge must not be one already
        const Tri& f = s.triangles[std::size_t(w)];
        if (std::count(f.begin(), f.end(), cv) && std::count(f.begin(), f.end(), d)) return false;
    }
    if (patchSmallestWedgeDeg(c, near, after, {}, sides) <= beforeDeg) return false;
    if (!patchIsClean(s, after, {}, near) || patchSweepsAVertex(s, near, {a, b, cv, d}, before, {}, after, {}, c.seeds)) return false;
    at.remove(t1, t);
    at.remove(s.triangles[std::size_t(u)], std::size_t(u));
    s.triangles[t] = after[0];
    s.triangles[std::size_t(u)] = after[1];
    at.add(after[0], t);
    at.add(after[1], std::size_t(u));
    c.sides[std::size_t(u)] = sides;
    return true;
}

double smallestOver(const InterfaceComplex& c, const std::vector<char>& repair, const TrianglesAt& at) {
    double deg = 360;
    for (std::size_t t = 0; t < c.surface.triangles.size(); ++t)
        if (repair[t]) deg = std::min(deg, wedgeOf(c, t, at));
    return deg;
}

}  // namespace

PatchWedgeStats openPatchWedges(InterfaceComplex& complex, std::vector<char>& repair, double minWedgeDeg, int maxPasses) {
    PatchWedgeStats stats;
    if (std::none_of(repair.begin(), repair.end(), [](char f) { return f != 0; })) return stats;
    TrianglesAt at(complex.surface);
    stats.smallestWedgeBeforeDeg = smallestOver(complex, repair, at);
    for (int pass = 0; pass < maxPasses; ++pass) {
        std::size_t made = 0;
        for (std::size_t t = 0; t < complex.surface.triangles.size(); ++t)
            for (std::size_t k = 0; k < 3 && repair[t]; ++k)
                if (flip(complex, repair, at, t, k, minWedgeDeg)) {
                    ++made;
                    break;  // t changed: its other edges next pass
                }
        stats.flips += made;
        if (made == 0) break;
    }
    for (int pass = 0; pass < maxPasses; ++pass) {
        std::size_t made = 0;
        const std::size_t count = complex.surface.triangles.size();
        for (std::size_t t = 0; t < count; ++t)
            if (repair[t] && bump(complex, repair, at, t, minWedgeDeg)) ++made;
        stats.bumps += made;
        if (made == 0) break;
    }
    stats.smallestWedgeAfterDeg = smallestOver(complex, repair, at);
    return stats;
}

}  // namespace jawmesh
