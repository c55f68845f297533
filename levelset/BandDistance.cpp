// Implements levelset/BandDistance.h; what it computes, its rules and its contract are documented there.
#include "levelset/BandDistance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif
#include <limits>
#include <memory>

namespace jawmesh {

namespace {
using LeafT = openvdb::FloatTree::LeafNodeType;
constexpr int kLeafLog2 = 3;
constexpr int kLeafDim = 1 << kLeafLog2;  // 8
static_assert(LeafT::DIM == kLeafDim, "bandDistance assumes 8^3 leaf nodes");

inline int leafOf(int voxel) { return voxel >> kLeafLog2; }  // floor division, also below zero

// Triangles thinner than this (voxels) are measured as their three edges: their normal is noise.
constexpr double kFlatHeightVoxels = 1e-4;

// One triangle in the frame of one leaf (corners relative to the leaf origin, so float suffices).
// Plane: h = n.P - hn. Edge k runs from v[k] to v[k+1]; e_k = m_k.P - c_k > 0 outside it (a flat
// triangle has e_k = 1 everywhere, so it is measured by its edges alone). Projected on xy, the
// triangle widened by r lies where q_k.(x, y) - o_k < r for all k (q_k = 0, o_k = +inf when the
// projection is too thin to orient, so the edge never binds).
struct LocalTriangle {
    float v[3][3];
    float edge[3][3];
    float invLen2[3];
    float n[3], hn;
    float m[3][3], c[3];
    float q[3][2], o[3];
    float lo[3], hi[3];  // bounding box of the corners
};

LocalTriangle localTriangle(const std::vector<Vec3>& vx, const Tri& tri, const Vec3& origin) {
    LocalTriangle t{};
    Vec3 p[3];
    for (int k = 0; k < 3; ++k) p[k] = vx[static_cast<std::size_t>(tri[k])] - origin;
    Vec3 e[3];
    double longest2 = 0;
    for (int k = 0; k < 3; ++k) {
        e[k] = p[(k + 1) % 3] - p[k];
        const double len2 = e[k].squaredNorm();
        longest2 = std::max(longest2, len2);
        t.invLen2[k] = len2 > 0 ? static_cast<float>(1.0 / len2) : 0.0f;
        for (int d = 0; d < 3; ++d) {
            t.v[k][d] = static_cast<float>(p[k][d]);
            t.edge[k][d] = static_cast<float>(e[k][d]);
        }
    }
    for (int d = 0; d < 3; ++d) {
        t.lo[d] = std::min({t.v[0][d], t.v[1][d], t.v[2][d]});
        t.hi[d] = std::max({t.v[0][d], t.v[1][d], t.v[2][d]});
    }
    // xy projection: outward edge normals when its orientation is numerically clear.
    const double area2xy = e[0].x() * e[1].y() - e[0].y() * e[1].x();
    const bool orientedXy = std::abs(area2xy) > 1e-6 * longest2;
    for (int k = 0; k < 3; ++k) {
        const double len = std::sqrt(e[k].x() * e[k].x() + e[k].y() * e[k].y());
        if (!orientedXy || len == 0.0) {
            t.o[k] = std::numeric_limits<float>::max();  // q_k.(x, y) - o_k never binds
            continue;
        }
        const double s = area2xy > 0 ? 1.0 : -1.0;
        const double qx = s * e[k].y() / len, qy = -s * e[k].x() / len;
        t.q[k][0] = static_cast<float>(qx);
        t.q[k][1] = static_cast<float>(qy);
        t.o[k] = static_cast<float>(qx * p[k].x() + qy * p[k].y());
    }
    const Vec3 cross = e[0].cross(e[1]);
    const double area2 = cross.norm();
    if (!(area2 > kFlatHeightVoxels * std::sqrt(longest2))) {
        t.c[0] = t.c[1] = t.c[2] = -1.0f;
        return t;
    }
    const Vec3 n = cross / area2;
    for (int d = 0; d < 3; ++d) t.n[d] = static_cast<float>(n[d]);
    t.hn = static_cast<float>(n.dot(p[0]));
    for (int k = 0; k < 3; ++k) {
        const Vec3 m = e[k].cross(n).normalized();  // in-plane, pointing away from the triangle
        for (int d = 0; d < 3; ++d) t.m[k][d] = static_cast<float>(m[d]);
        t.c[k] = static_cast<float>(m.dot(p[k]));
    }
    return t;
}

// Four floats (GCC/Clang vector extension: SIMD on any target, SSE on x86-64).
typedef float Quad __attribute__((vector_size(16)));
typedef std::int32_t QuadMask __attribute__((vector_size(16)));

inline Quad splat(float a) { return Quad{a, a, a, a}; }

#if defined(__SSE__)
inline bool any(QuadMask m) { return _mm_movemask_ps(reinterpret_cast<__m128>(m)) != 0; }
#else
inline bool any(QuadMask m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }
#endif
inline Quad minOf(Quad a, Quad b) { return a < b ? a : b; }
inline Quad maxOf(Quad a, Quad b) { return a > b ? a : b; }

// Squared distance from the points (x, y, z) to edge k.
inline Quad edgeDistance2(const LocalTriangle& t, int k, float x, float y, Quad z) {
    const float px = x - t.v[k][0], py = y - t.v[k][1];
    const Quad pz = z - t.v[k][2];
    Quad s = ((t.edge[k][0] * px + t.edge[k][1] * py) + t.edge[k][2] * pz) * t.invLen2[k];
    s = s < 0.0f ? splat(0.0f) : s;
    s = s > 1.0f ? splat(1.0f) : s;
    const Quad qx = px - s * t.edge[k][0], qy = py - s * t.edge[k][1], qz = pz - s * t.edge[k][2];
    return qx * qx + qy * qy + qz * qz;
}

// Lowers out[0..4) (squared distances of four voxels of a column along z, z = z0 + 0..3) by one
// triangle: the plane distance over the triangle, else the distance to the nearest edge beyond
// which the voxel lies. A lower bound (plane distance and distance to the farthest edge's
// half-plane) skips the edges, or the whole quad, that cannot improve on out[].
inline void quad(const LocalTriangle& t, float x, float y, float z0, float* out) {
    Quad best;
    std::memcpy(&best, out, sizeof best);
    const Quad z = Quad{0.0f, 1.0f, 2.0f, 3.0f} + z0;
    const Quad h = (t.n[0] * x + t.n[1] * y - t.hn) + t.n[2] * z;
    Quad e[3];
    for (int k = 0; k < 3; ++k) e[k] = (t.m[k][0] * x + t.m[k][1] * y - t.c[k]) + t.m[k][2] * z;
    const Quad beyond = maxOf(maxOf(maxOf(e[0], e[1]), e[2]), splat(0.0f));
    const Quad h2 = h * h;
    const QuadMask open = (h2 + beyond * beyond) < best;
    if (!any(open)) return;
    const QuadMask over = beyond <= 0.0f;
    Quad d2 = splat(std::numeric_limits<float>::max());
    for (int k = 0; k < 3; ++k)
        if (any(open & (e[k] > 0.0f))) d2 = minOf(d2, edgeDistance2(t, k, x, y, z));
    best = minOf(best, over ? h2 : d2);
    std::memcpy(out, &best, sizeof best);
}

inline void column(const LocalTriangle& t, float x, float y, float* out) {
    quad(t, x, y, 0.0f, out);
    quad(t, x, y, 4.0f, out + 4);
}

// Lowers best[] (squared index-space distances of the leaf's voxels) by one triangle, one
// column along z at a time, skipping columns out of reach in xy or in the plane's slab.
void rasteriseBand(const LocalTriangle& t, float r, float* best) {
    int lo[2], hi[2];
    for (int d = 0; d < 2; ++d) {
        lo[d] = std::max(0, static_cast<int>(std::ceil(t.lo[d] - r)));
        hi[d] = std::min(kLeafDim - 1, static_cast<int>(std::floor(t.hi[d] + r)));
        if (lo[d] > hi[d]) return;
    }
    if (t.lo[2] - r >= kLeafDim - 1 || t.hi[2] + r <= 0.0f) return;
    for (int x = lo[0]; x <= hi[0]; ++x) {
        const float fx = static_cast<float>(x);
        for (int y = lo[1]; y <= hi[1]; ++y) {
            const float fy = static_cast<float>(y);
            // Lower bounds along the whole column: distance in xy to the projected triangle,
            // and the least |h| over z = 0..7 (h is linear in z).
            const float inPlane = std::max({t.q[0][0] * fx + t.q[0][1] * fy - t.o[0], t.q[1][0] * fx + t.q[1][1] * fy - t.o[1],
                                            t.q[2][0] * fx + t.q[2][1] * fy - t.o[2], 0.0f});
            const float hA = t.n[0] * fx + t.n[1] * fy - t.hn, hB = hA + t.n[2] * (kLeafDim - 1);
            const float slab = hA > 0.0f && hB > 0.0f ? std::min(hA, hB) : (hA < 0.0f && hB < 0.0f ? -std::max(hA, hB) : 0.0f);
            const float bound = std::max(inPlane, slab);
            float* out = best + ((x << 6) | (y << 3));
            if (bound * bound >= *std::max_element(out, out + kLeafDim)) continue;
            column(t, fx, fy, out);
        }
    }
}

// Normal of a triangle (index space) and whether it is too thin to trust it.
bool planeOf(const std::vector<Vec3>& vx, const Tri& tri, Vec3& n, double& offset) {
    const Vec3& a = vx[static_cast<std::size_t>(tri[0])];
    const Vec3& b = vx[static_cast<std::size_t>(tri[1])];
    const Vec3& c = vx[static_cast<std::size_t>(tri[2])];
    const Vec3 cross = (b - a).cross(c - a);
    const double longest = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
    const double area2 = cross.norm();
    if (!(area2 > kFlatHeightVoxels * longest)) return false;
    n = cross / area2;
    offset = n.dot(a);
    return true;
}

// One (triangle, leaf) pair of a leaf column; nearness = squared distance from the leaf centre to
// the triangle's centroid, so that each leaf meets its nearest triangles first.
struct Entry {
    std::int32_t leafZ;
    float nearness;
    std::uint32_t triangle;
};
/// Voxel range of a triangle's bounding box widened by r voxels.
void voxelRange(const std::vector<Vec3>& vx, const Tri& tri, double r, openvdb::Coord& lo, openvdb::Coord& hi) {
    for (int d = 0; d < 3; ++d) {
        double a = vx[static_cast<std::size_t>(tri[0])][d], b = a;
        for (int k = 1; k < 3; ++k) {
            a = std::min(a, vx[static_cast<std::size_t>(tri[k])][d]);
            b = std::max(b, vx[static_cast<std::size_t>(tri[k])][d]);
        }
        lo[d] = static_cast<int>(std::ceil(a - r));
        hi[d] = static_cast<int>(std::floor(b + r));
    }
}

/// Each triangle's band radius (voxels): the full half width when its box widened by it reaches a
/// wide box, the far one otherwise. Then every voxel of a wide box meets each triangle within the
/// full half width of it, and every other voxel each triangle within the far half width.
struct Radii {
    double wide = 0, far = 0;
    std::vector<char> isWide;  ///< per triangle; empty when far == wide
    double of(std::size_t t) const { return isWide.empty() || isWide[t] ? wide : far; }
};

Radii radiiOf(const std::vector<Vec3>& vx, const std::vector<Tri>& triangles, const BandWidths& widths) {
    Radii r{widths.halfWidthVoxels, std::min(widths.farHalfWidthVoxels, widths.halfWidthVoxels), {}};
    if (!(r.far < r.wide)) return r;
    r.isWide.assign(triangles.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 4096), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t t = range.begin(); t < range.end(); ++t) {
            openvdb::Coord lo, hi;
            voxelRange(vx, triangles[t], r.wide, lo, hi);
            const openvdb::CoordBBox box(lo, hi);
            for (const openvdb::CoordBBox& w : widths.wideBoxes) r.isWide[t] = r.isWide[t] || w.hasOverlap(box);
        }
    });
    return r;
}

/// The wide boxes that reach the leaf at `origin` (most leaves: none or one), so that its voxels
/// test only those.
void wideBoxesAt(const BandWidths& widths, const openvdb::Coord& origin, std::vector<openvdb::CoordBBox>& out) {
    out.clear();
    const openvdb::CoordBBox leaf(origin, origin.offsetBy(kLeafDim - 1));
    for (const openvdb::CoordBBox& w : widths.wideBoxes)
        if (w.hasOverlap(leaf)) out.push_back(w);
}

/// Whether voxel c keeps a value whose square is d2 (voxels^2): under the full half width in a
/// wide box (`wideHere`: those reaching its leaf), under the far one elsewhere.
bool inBand(const Radii& radii, const std::vector<openvdb::CoordBBox>& wideHere, const openvdb::Coord& c, float d2) {
    if (radii.isWide.empty() || d2 < float(radii.far * radii.far)) return true;
    for (const openvdb::CoordBBox& w : wideHere)
        if (w.isInside(c)) return true;
    return false;
}

/// The leaf columns (x, y) that the triangles' widened boxes cover.
struct LeafColumns {
    openvdb::Coord leafMin{std::numeric_limits<int>::max()}, leafMax{std::numeric_limits<int>::min()};
    std::size_t ny = 0, count = 0;
    std::size_t of(int lx, int ly) const {
        return static_cast<std::size_t>(lx - leafMin.x()) * ny + static_cast<std::size_t>(ly - leafMin.y());
    }
};

LeafColumns leafColumns(const std::vector<Vec3>& vx, const std::vector<Tri>& triangles, const Radii& r) {
    LeafColumns c;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        openvdb::Coord lo, hi;
        voxelRange(vx, triangles[t], r.of(t), lo, hi);
        for (int d = 0; d < 3; ++d) {
            c.leafMin[d] = std::min(c.leafMin[d], leafOf(lo[d]));
            c.leafMax[d] = std::max(c.leafMax[d], leafOf(hi[d]));
        }
    }
    const std::size_t nx = static_cast<std::size_t>(c.leafMax.x() - c.leafMin.x() + 1);
    c.ny = static_cast<std::size_t>(c.leafMax.y() - c.leafMin.y() + 1);
    c.count = nx * c.ny;
    return c;
}

/// Calls emit(column, leafZ, nearness) for every leaf the triangle's band may reach: inside the
/// widened bounding box and not farther than r from the triangle's plane.
template <typename Emit>
void forEachLeaf(const std::vector<Vec3>& vx, const Tri& tri, double r, const LeafColumns& columns, Emit&& emit) {
    openvdb::Coord lo, hi;
    voxelRange(vx, tri, r, lo, hi);
    Vec3 n;
    double offset = 0;
    const bool planar = planeOf(vx, tri, n, offset);
    const double halfExtent = 0.5 * (kLeafDim - 1) * (std::abs(n.x()) + std::abs(n.y()) + std::abs(n.z()));
    const Vec3 centroid = (vx[static_cast<std::size_t>(tri[0])] + vx[static_cast<std::size_t>(tri[1])] +
                           vx[static_cast<std::size_t>(tri[2])]) / 3.0;
    for (int lx = leafOf(lo.x()); lx <= leafOf(hi.x()); ++lx)
        for (int ly = leafOf(lo.y()); ly <= leafOf(hi.y()); ++ly) {
            const std::size_t col = columns.of(lx, ly);
            for (int lz = leafOf(lo.z()); lz <= leafOf(hi.z()); ++lz) {
                const Vec3 centre = Vec3(lx, ly, lz) * kLeafDim + Vec3::Constant(0.5 * (kLeafDim - 1));
                if (planar && std::abs(n.dot(centre) - offset) - halfExtent >= r) continue;
                emit(col, lz, static_cast<float>((centroid - centre).squaredNorm()));
            }
        }
}

/// (triangle, leaf) pairs bucketed by leaf column: count, prefix sum, fill. offsets[c] is where
/// column c starts in the entries (offsets has one more element than columns).
std::vector<Entry> bucketByColumn(const std::vector<Vec3>& vx, const std::vector<Tri>& triangles, const Radii& r,
                                  const LeafColumns& columns, std::vector<std::uint64_t>& offsets, Progress& progress) {
    constexpr std::size_t kGrain = 4096;
    std::vector<std::atomic<std::uint64_t>> cursor(columns.count);
    for (auto& c : cursor) c.store(0, std::memory_order_relaxed);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), kGrain), [&](const tbb::blocked_range<std::size_t>& range) {
        progress.checkCancelled();
        for (std::size_t t = range.begin(); t < range.end(); ++t)
            forEachLeaf(vx, triangles[t], r.of(t), columns,
                        [&](std::size_t col, int, float) { cursor[col].fetch_add(1, std::memory_order_relaxed); });
    });
    offsets.assign(columns.count + 1, 0);
    std::uint64_t total = 0;
    for (std::size_t c = 0; c < columns.count; ++c) {
        offsets[c] = total;
        total += cursor[c].load(std::memory_order_relaxed);
        cursor[c].store(offsets[c], std::memory_order_relaxed);
    }
    offsets[columns.count] = total;
    std::vector<Entry> entries(total);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), kGrain), [&](const tbb::blocked_range<std::size_t>& range) {
        progress.checkCancelled();
        for (std::size_t t = range.begin(); t < range.end(); ++t)
            forEachLeaf(vx, triangles[t], r.of(t), columns, [&](std::size_t col, int lz, float nearness) {
                entries[cursor[col].fetch_add(1, std::memory_order_relaxed)] = {lz, nearness, static_cast<std::uint32_t>(t)};
            });
    });
    return entries;
}

/// The leaves of one column [b, e) of entries: sorted by leaf, nearest triangles first (they
/// tighten best[] so that the bounds reject the rest; the triangle index breaks ties so the order
/// is canonical), then one leaf per run of equal leafZ.
void rasteriseColumn(const std::vector<Vec3>& vx, const std::vector<Tri>& triangles, Entry* b, Entry* e, int lx, int ly,
                     const BandWidths& widths, const Radii& radii, double voxelSizeMm, float background,
                     std::vector<std::unique_ptr<LeafT>>& out) {
    const float r2 = static_cast<float>(radii.wide * radii.wide);
    // Active values stay below the background even where float rounding would reach it.
    const float insideBand = std::nextafter(background, 0.0f);
    float best[LeafT::SIZE];
    std::vector<openvdb::CoordBBox> wideHere;
    std::sort(b, e, [](const Entry& p, const Entry& q) {
        if (p.leafZ != q.leafZ) return p.leafZ < q.leafZ;
        if (p.nearness != q.nearness) return p.nearness < q.nearness;
        return p.triangle < q.triangle;
    });
    for (Entry* run = b; run != e;) {
        Entry* runEnd = run;
        while (runEnd != e && runEnd->leafZ == run->leafZ) ++runEnd;
        const openvdb::Coord origin(lx * kLeafDim, ly * kLeafDim, run->leafZ * kLeafDim);
        const Vec3 originVec(origin.x(), origin.y(), origin.z());
        std::fill(best, best + LeafT::SIZE, r2);
        for (Entry* p = run; p != runEnd; ++p)
            rasteriseBand(localTriangle(vx, triangles[p->triangle], originVec), static_cast<float>(radii.of(p->triangle)), best);
        wideBoxesAt(widths, origin, wideHere);
        std::unique_ptr<LeafT> leaf;
        for (openvdb::Index i = 0; i < LeafT::SIZE; ++i) {
            if (!(best[i] < r2) || !inBand(radii, wideHere, origin + LeafT::offsetToLocalCoord(i), best[i])) continue;
            if (!leaf) leaf = std::make_unique<LeafT>(origin, background, false);
            leaf->setValueOn(i, std::min(static_cast<float>(std::sqrt(best[i]) * voxelSizeMm), insideBand));
        }
        if (leaf) out.push_back(std::move(leaf));
        run = runEnd;
    }
}

}  // namespace

openvdb::FloatTree::Ptr bandDistance(const std::vector<Vec3>& vx, const std::vector<Tri>& triangles, double voxelSizeMm,
                                     double halfWidthVoxels, Progress& progress) {
    return bandDistance(vx, triangles, voxelSizeMm, BandWidths{halfWidthVoxels, halfWidthVoxels, {}}, progress);
}

openvdb::FloatTree::Ptr bandDistance(const std::vector<Vec3>& vx, const std::vector<Tri>& triangles, double voxelSizeMm,
                                     const BandWidths& widths, Progress& progress) {
    const float background = static_cast<float>(widths.halfWidthVoxels * voxelSizeMm);
    auto tree = std::make_shared<openvdb::FloatTree>(background);
    if (triangles.empty()) return tree;
    const Radii r = radiiOf(vx, triangles, widths);
    const LeafColumns columns = leafColumns(vx, triangles, r);
    std::vector<std::uint64_t> offsets;
    std::vector<Entry> entries = bucketByColumn(vx, triangles, r, columns, offsets, progress);
    progress.update(0.1);

    std::vector<std::vector<std::unique_ptr<LeafT>>> leaves(columns.count);
    std::atomic<std::size_t> columnsDone{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, columns.count, 16), [&](const tbb::blocked_range<std::size_t>& range) {
        progress.checkCancelled();
        for (std::size_t col = range.begin(); col < range.end(); ++col) {
            const int lx = columns.leafMin.x() + static_cast<int>(col / columns.ny);
            const int ly = columns.leafMin.y() + static_cast<int>(col % columns.ny);
            rasteriseColumn(vx, triangles, entries.data() + offsets[col], entries.data() + offsets[col + 1], lx, ly, widths, r,
                            voxelSizeMm, background, leaves[col]);
            const std::size_t done = ++columnsDone;
            if (done % 1024 == 0) progress.update(0.1 + 0.85 * static_cast<double>(done) / static_cast<double>(columns.count));
        }
    });
    std::vector<Entry>().swap(entries);

    for (auto& column : leaves)
        for (auto& leaf : column) tree->addLeaf(leaf.release());
    progress.update(1.0);
    return tree;
}

}  // namespace jawmesh
