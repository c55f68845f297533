// Implements levelset/ScanlineWinding.h; what it computes, its rules and its contract are documented there.
#include "levelset/ScanlineWinding.h"

#include "io/Error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

namespace jawmesh {

namespace {
struct P2 {
    double u, v;
};

// Edge function of the directed edge lo -> hi at q, lo/hi picked by vertex index so that both
// triangles of a shared edge compute the same bits.
inline double canonicalEdge(const P2& lo, const P2& hi, double qu, double qv) {
    return (hi.u - lo.u) * (qv - lo.v) - (hi.v - lo.v) * (qu - lo.u);
}

// Top-left rule for a counter-clockwise edge direction (du, dv): exactly one of d and -d passes.
inline bool ownsBoundary(double du, double dv) { return dv < 0.0 || (dv == 0.0 && du < 0.0); }

// Calls emit(u, v, pos, dir) for every line of the axis that the triangle crosses.
template <typename Emit>
void rasteriseCrossings(const std::vector<Vec3>& vx, const Tri& tri, int axis, Emit&& emit) {
    const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
    P2 p[3];
    double w[3];
    for (int k = 0; k < 3; ++k) {
        const Vec3& x = vx[static_cast<std::size_t>(tri[k])];
        p[k] = {x[ua], x[va]};
        w[k] = x[axis];
    }
    const double area = (p[1].u - p[0].u) * (p[2].v - p[0].v) - (p[1].v - p[0].v) * (p[2].u - p[0].u);
    if (area == 0.0) return;  // parallel to the axis: crossed by no line, neighbours close the gap
    const double s = area > 0.0 ? 1.0 : -1.0;
    // The normal's component along the axis has the sign of area: positive means leaving.
    const int dir = area > 0.0 ? -1 : 1;
    const double uLo = std::min({p[0].u, p[1].u, p[2].u}), uHi = std::max({p[0].u, p[1].u, p[2].u});
    const double vLo = std::min({p[0].v, p[1].v, p[2].v}), vHi = std::max({p[0].v, p[1].v, p[2].v});
    const int iu0 = static_cast<int>(std::ceil(uLo)), iu1 = static_cast<int>(std::floor(uHi));
    const int iv0 = static_cast<int>(std::ceil(vLo)), iv1 = static_cast<int>(std::floor(vHi));
    bool forward[3];
    bool owns[3];
    for (int k = 0; k < 3; ++k) {
        const int e = (k + 1) % 3;
        forward[k] = tri[k] < tri[e];
        owns[k] = ownsBoundary(s * (p[e].u - p[k].u), s * (p[e].v - p[k].v));
    }
    for (int iu = iu0; iu <= iu1; ++iu) {
        for (int iv = iv0; iv <= iv1; ++iv) {
            double e[3];
            bool in = true;
            for (int k = 0; k < 3 && in; ++k) {
                const int j = (k + 1) % 3;
                const double f = forward[k] ? canonicalEdge(p[k], p[j], iu, iv) : -canonicalEdge(p[j], p[k], iu, iv);
                e[k] = s * f;
                in = e[k] > 0.0 || (e[k] == 0.0 && owns[k]);
            }
            if (!in) continue;
            const double sum = e[0] + e[1] + e[2];
            // e[k] weighs the corner opposite edge k.
            const double pos = sum > 0.0 ? (e[1] * w[0] + e[2] * w[1] + e[0] * w[2]) / sum : (w[0] + w[1] + w[2]) / 3.0;
            emit(iu, iv, pos, dir);
        }
    }
}
}  // namespace

ScanlineWinding::ScanlineWinding(const std::vector<Vec3>& vx, const std::vector<Tri>& triangles, Progress& progress) {
    BBox box;
    for (const Tri& t : triangles)
        for (auto i : t) box.extend(vx[static_cast<std::size_t>(i)]);
    if (box.empty()) return;
    const std::size_t n = triangles.size();
    constexpr std::size_t kGrain = 4096;
    for (int axis = 0; axis < 3; ++axis) {
        Axis& ax = axes_[static_cast<std::size_t>(axis)];
        const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
        ax.uMin = static_cast<int>(std::ceil(box.min[ua]));
        ax.vMin = static_cast<int>(std::ceil(box.min[va]));
        ax.nu = std::max(0, static_cast<int>(std::floor(box.max[ua])) - ax.uMin + 1);
        ax.nv = std::max(0, static_cast<int>(std::floor(box.max[va])) - ax.vMin + 1);
        const std::size_t lines = static_cast<std::size_t>(ax.nu) * static_cast<std::size_t>(ax.nv);
        if (lines == 0) continue;
        auto lineOf = [&ax](int u, int v) {
            return static_cast<std::size_t>(u - ax.uMin) * static_cast<std::size_t>(ax.nv) + static_cast<std::size_t>(v - ax.vMin);
        };

        std::vector<std::atomic<std::uint32_t>> cursor(lines);
        for (auto& c : cursor) c.store(0, std::memory_order_relaxed);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
            progress.checkCancelled();
            for (std::size_t t = r.begin(); t < r.end(); ++t)
                rasteriseCrossings(vx, triangles[t], axis, [&](int u, int v, double, int) {
                    cursor[lineOf(u, v)].fetch_add(1, std::memory_order_relaxed);
                });
        });
        ax.offsets.resize(lines + 1);
        std::uint64_t total = 0;
        for (std::size_t l = 0; l < lines; ++l) {
            ax.offsets[l] = static_cast<std::uint32_t>(total);
            total += cursor[l].load(std::memory_order_relaxed);
            cursor[l].store(ax.offsets[l], std::memory_order_relaxed);
        }
        if (total > std::numeric_limits<std::uint32_t>::max()) throw Error("too many surface crossings; use a larger voxel");
        ax.offsets[lines] = static_cast<std::uint32_t>(total);
        ax.crossings.resize(total);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
            progress.checkCancelled();
            for (std::size_t t = r.begin(); t < r.end(); ++t)
                rasteriseCrossings(vx, triangles[t], axis, [&](int u, int v, double pos, int dir) {
                    const std::uint32_t slot = cursor[lineOf(u, v)].fetch_add(1, std::memory_order_relaxed);
                    ax.crossings[slot] = {static_cast<float>(pos), dir};
                });
        });
        // The fill order above depends on scheduling; sorting each line makes it canonical.
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lines, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t l = r.begin(); l < r.end(); ++l) {
                Crossing* b = ax.crossings.data() + ax.offsets[l];
                Crossing* e = ax.crossings.data() + ax.offsets[l + 1];
                std::sort(b, e, [](const Crossing& x, const Crossing& y) {
                    return x.pos < y.pos || (x.pos == y.pos && x.winding < y.winding);
                });
                std::int32_t w = 0;
                for (Crossing* c = b; c != e; ++c) {
                    w += c->winding;
                    c->winding = w;
                }
            }
        });
        progress.update((axis + 1) / 3.0);
    }
}

bool ScanlineWinding::windings(int axis, int u, int v, int start, int count, int* out) const {
    const Axis& ax = axes_[static_cast<std::size_t>(axis)];
    if (u < ax.uMin || v < ax.vMin || u >= ax.uMin + ax.nu || v >= ax.vMin + ax.nv) {
        std::fill(out, out + count, 0);
        return true;
    }
    const std::size_t l = static_cast<std::size_t>(u - ax.uMin) * static_cast<std::size_t>(ax.nv) + static_cast<std::size_t>(v - ax.vMin);
    const Crossing* b = ax.crossings.data() + ax.offsets[l];
    const Crossing* e = ax.crossings.data() + ax.offsets[l + 1];
    if (b != e && e[-1].winding != 0) return false;
    const Crossing* c = std::upper_bound(b, e, static_cast<float>(start), [](float x, const Crossing& k) { return x < k.pos; });
    for (int i = 0; i < count; ++i) {
        const float x = static_cast<float>(start + i);
        while (c != e && c->pos <= x) ++c;
        out[i] = c == b ? 0 : c[-1].winding;
    }
    return true;
}

std::size_t ScanlineWinding::crossingCount() const {
    std::size_t n = 0;
    for (const Axis& a : axes_) n += a.crossings.size();
    return n;
}

}  // namespace jawmesh
