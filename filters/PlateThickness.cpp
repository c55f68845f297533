// Implements filters/PlateThickness.h; what it computes, its rules and its contract are documented there.
#include "filters/PlateThickness.h"

#include "filters/RayTriangle.h"
#include "io/Angles.h"
#include "io/VertexTriangles.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace jawmesh {
namespace {


/// The triangles of one slab in a uniform grid of cell `cell` (sorted (cell key, triangle) pairs).
class SlabGrid {
public:
    SlabGrid(const Vec3& origin, double cell) : origin_(origin), cell_(cell) {}

    void add(std::int32_t t, const Vec3& lo, const Vec3& hi) {
        const auto a = cellOf(lo), b = cellOf(hi);
        for (std::int64_t x = a[0]; x <= b[0]; ++x)
            for (std::int64_t y = a[1]; y <= b[1]; ++y)
                for (std::int64_t z = a[2]; z <= b[2]; ++z) entries_.emplace_back(key(x, y, z), t);
    }
    void finish() { std::sort(entries_.begin(), entries_.end()); }

    /// Calls f(t) for every triangle in a cell that the box lo..hi meets (a triangle may come twice).
    template <typename F>
    void query(const Vec3& lo, const Vec3& hi, F&& f) const {
        const auto a = cellOf(lo), b = cellOf(hi);
        for (std::int64_t x = a[0]; x <= b[0]; ++x)
            for (std::int64_t y = a[1]; y <= b[1]; ++y)
                for (std::int64_t z = a[2]; z <= b[2]; ++z) {
                    const std::uint64_t k = key(x, y, z);
                    auto it = std::lower_bound(entries_.begin(), entries_.end(), std::make_pair(k, std::int32_t(-1)));
                    for (; it != entries_.end() && it->first == k; ++it) f(it->second);
                }
    }

private:
    std::array<std::int64_t, 3> cellOf(const Vec3& p) const {
        return {std::int64_t(std::floor((p.x() - origin_.x()) / cell_)), std::int64_t(std::floor((p.y() - origin_.y()) / cell_)),
                std::int64_t(std::floor((p.z() - origin_.z()) / cell_))};
    }
    static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) {
        return (std::uint64_t(x) & 0x1fffff) << 42 | (std::uint64_t(y) & 0x1fffff) << 21 | (std::uint64_t(z) & 0x1fffff);
    }
    Vec3 origin_;
    double cell_;
    std::vector<std::pair<std::uint64_t, std::int32_t>> entries_;
};

}  // namespace

std::vector<float> plateThicknessMm(const InterfaceComplex& complex, const std::vector<char>& measure,
                                    const PlateOptions& options) {
    const auto& V = complex.surface.vertices;
    const auto& T = complex.surface.triangles;
    std::vector<float> thickness(V.size(), std::numeric_limits<float>::infinity());
    if (V.empty() || T.empty() || !(options.maxMm > 0)) return thickness;
    const double maxMm = options.maxMm;
    const double cosPlate = std::cos(options.maxAngleDeg * kPi / 180.0);

    const VertexTriangles around = vertexTriangles(T, V.size());
    std::vector<Vec3> normal(T.size());  // unit, into sides[t][0]
    std::vector<float> minX(T.size()), maxX(T.size());
    float widest = 0;
    BBox box;
    for (std::size_t t = 0; t < T.size(); ++t) {
        const Vec3 &a = V[std::size_t(T[t][0])], &b = V[std::size_t(T[t][1])], &c = V[std::size_t(T[t][2])];
        const Vec3 n = (b - a).cross(c - a);
        normal[t] = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
        minX[t] = float(std::min({a.x(), b.x(), c.x()}));
        maxX[t] = float(std::max({a.x(), b.x(), c.x()}));
        widest = std::max(widest, maxX[t] - minX[t]);
        box.extend(a);
        box.extend(b);
        box.extend(c);
    }
    // Triangles and vertices by x, cut into slabs processed independently.
    std::vector<std::int32_t> byX(T.size());
    std::iota(byX.begin(), byX.end(), 0);
    std::sort(byX.begin(), byX.end(), [&](std::int32_t a, std::int32_t b) { return minX[std::size_t(a)] < minX[std::size_t(b)] || (minX[std::size_t(a)] == minX[std::size_t(b)] && a < b); });
    std::vector<std::int32_t> verts;
    for (std::size_t v = 0; v < V.size(); ++v)
        if ((measure.empty() || measure[v]) && around.count(std::int32_t(v)) > 0) verts.push_back(std::int32_t(v));
    std::sort(verts.begin(), verts.end(), [&](std::int32_t a, std::int32_t b) { return V[std::size_t(a)].x() < V[std::size_t(b)].x() || (V[std::size_t(a)].x() == V[std::size_t(b)].x() && a < b); });
    const double slabMm = std::max(1.0, 4.0 * maxMm);
    const std::size_t slabs = std::size_t(std::ceil((box.max.x() - box.min.x()) / slabMm)) + 1;
    const Vec3 origin = box.min - Vec3::Constant(2 * maxMm);

    tbb::parallel_for(std::size_t(0), slabs, [&](std::size_t s) {
        const double x0 = box.min.x() + double(s) * slabMm, x1 = x0 + slabMm;
        const auto vb = std::lower_bound(verts.begin(), verts.end(), x0, [&](std::int32_t v, double x) { return V[std::size_t(v)].x() < x; });
        const auto ve = s + 1 == slabs ? verts.end()
                                       : std::lower_bound(vb, verts.end(), x1, [&](std::int32_t v, double x) { return V[std::size_t(v)].x() < x; });
        if (vb == ve) return;
        SlabGrid grid(origin, maxMm);
        const auto tb = std::lower_bound(byX.begin(), byX.end(), x0 - maxMm - widest, [&](std::int32_t t, double x) { return minX[std::size_t(t)] < x; });
        for (auto it = tb; it != byX.end() && minX[std::size_t(*it)] <= x1 + maxMm; ++it) {
            const std::size_t t = std::size_t(*it);
            if (maxX[t] < x0 - maxMm) continue;
            Vec3 lo = V[std::size_t(T[t][0])], hi = lo;
            for (int k = 1; k < 3; ++k) {
                lo = lo.cwiseMin(V[std::size_t(T[t][std::size_t(k)])]);
                hi = hi.cwiseMax(V[std::size_t(T[t][std::size_t(k)])]);
            }
            grid.add(std::int32_t(t), lo, hi);
        }
        grid.finish();

        struct Sheet {
            Label lo, hi;
            Vec3 n;  // area-weighted, into lo
        };
        std::vector<Sheet> sheets;
        for (auto vi = vb; vi != ve; ++vi) {
            const std::int32_t p = *vi;
            const Vec3& o = V[std::size_t(p)];
            sheets.clear();
            for (const std::int32_t* ti = around.begin(p); ti != around.end(p); ++ti) {
                const std::size_t t = std::size_t(*ti);
                const auto& sd = complex.sides[t];
                const Label lo = std::min(sd[0], sd[1]), hi = std::max(sd[0], sd[1]);
                const Tri& f = T[t];
                const Vec3 n2 = (V[std::size_t(f[1])] - V[std::size_t(f[0])]).cross(V[std::size_t(f[2])] - V[std::size_t(f[0])]);
                const Vec3 n = sd[0] == lo ? n2 : Vec3(-n2);
                auto it = std::find_if(sheets.begin(), sheets.end(), [&](const Sheet& x) { return x.lo == lo && x.hi == hi; });
                if (it == sheets.end()) sheets.push_back({lo, hi, n});
                else it->n += n;
            }
            float best = std::numeric_limits<float>::infinity();
            for (const Sheet& sh : sheets) {
                if (sh.n.norm() == 0) continue;
                const Vec3 n = sh.n.normalized();
                for (const auto& [region, dir] : {std::pair<Label, Vec3>{sh.lo, n}, std::pair<Label, Vec3>{sh.hi, -n}}) {
                    if (region == kOutsideLabel) continue;
                    const Vec3 end = o + maxMm * dir;
                    double hitT = std::numeric_limits<double>::infinity();
                    std::int32_t hit = -1;
                    grid.query(o.cwiseMin(end), o.cwiseMax(end), [&](std::int32_t t) {
                        const Tri& f = T[std::size_t(t)];
                        if (f[0] == p || f[1] == p || f[2] == p) return;
                        const double h = rayTriangleHit(o, dir, V[std::size_t(f[0])], V[std::size_t(f[1])], V[std::size_t(f[2])]);
                        if (h < hitT || (h == hitT && t < hit)) {
                            hitT = h;
                            hit = t;
                        }
                    });
                    if (hit < 0 || hitT > maxMm) continue;
                    const auto& hs = complex.sides[std::size_t(hit)];
                    if (hs[0] != region && hs[1] != region) continue;
                    // The sheet's normal there, over the triangles of its interface around the hit
                    // one: a fine triangle alone may lean by 45 degrees (voxel steps).
                    Vec3 into = Vec3::Zero();
                    for (std::int32_t q : T[std::size_t(hit)])
                        for (const std::int32_t* it = around.begin(q); it != around.end(q); ++it) {
                            const auto& qs = complex.sides[std::size_t(*it)];
                            if (qs[0] == hs[0] && qs[1] == hs[1]) into += normal[std::size_t(*it)];
                            else if (qs[0] == hs[1] && qs[1] == hs[0]) into -= normal[std::size_t(*it)];
                        }
                    if (hs[0] != region) into = -into;
                    if (-into.dot(dir) < cosPlate * into.norm()) continue;  // a wedge, or not leaving the region
                    best = std::min(best, float(hitT));
                }
            }
            thickness[std::size_t(p)] = best;
        }
    });
    return thickness;
}

}  // namespace jawmesh
