// Implements levelset/CarveMeasure.h; what it computes, its rules and its contract are documented there.
#include "levelset/CarveMeasure.h"

#include "io/Error.h"

#include <tbb/parallel_for.h>

#include <openvdb/tree/LeafManager.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace jawmesh {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::Vec3d;

const Coord kFace[6] = {Coord(1, 0, 0), Coord(-1, 0, 0), Coord(0, 1, 0), Coord(0, -1, 0), Coord(0, 0, 1), Coord(0, 0, -1)};

/// Points bucketed in the cubic cells of their bounding box (compressed rows), for nearest-point
/// queries. A dense grid, not a hash map: the cap exclusion's queries look at a hundred cells each,
/// mostly empty, and the map's look-ups were most of the carve's measurement.
class PointGrid {
public:
    PointGrid(std::vector<Vec3d> points, double cell) : points_(std::move(points)), cell_(cell) {
        if (points_.empty()) return;
        Vec3d lo = points_[0], hi = lo;
        for (const Vec3d& p : points_) lo = minComponent(lo, p), hi = maxComponent(hi, p);
        // Coarser cells where the box would need more than 4 M (a tooth's box needs about 0.2 M at
        // 0.25 mm): the nearest point is the same, found among more points per cell.
        for (;;) {
            lo_ = cellOf(lo);
            dim_ = cellOf(hi) - lo_ + Coord(1);
            if (double(dim_[0]) * double(dim_[1]) * double(dim_[2]) <= double(1 << 22)) break;
            cell_ *= 2;
        }
        start_.assign(std::size_t(dim_[0]) * std::size_t(dim_[1]) * std::size_t(dim_[2]) + 1, 0);
        for (const Vec3d& p : points_) ++start_[indexOf(cellOf(p) - lo_) + 1];
        for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
        std::vector<std::uint32_t> at(start_.begin(), start_.end() - 1);
        order_.resize(points_.size());
        for (std::size_t i = 0; i < points_.size(); ++i) order_[at[indexOf(cellOf(points_[i]) - lo_)]++] = std::uint32_t(i);
    }
    bool empty() const { return points_.empty(); }
    /// Distance to the nearest point, or +inf when none is within maxDist.
    double nearest(const Vec3d& p, double maxDist) const {
        if (points_.empty()) return std::numeric_limits<double>::infinity();
        const Coord c = cellOf(p);
        double best2 = maxDist * maxDist;
        const auto visit = [&](const Coord& q) {
            const Coord d = q - lo_;
            if (d[0] < 0 || d[1] < 0 || d[2] < 0 || d[0] >= dim_[0] || d[1] >= dim_[1] || d[2] >= dim_[2]) return;
            const std::size_t i = indexOf(d);
            for (std::uint32_t k = start_[i]; k < start_[i + 1]; ++k) best2 = std::min(best2, (points_[order_[k]] - p).lengthSqr());
        };
        const int rings = int(std::ceil(maxDist / cell_));
        for (int r = 0; r <= rings; ++r) {
            // Every point in ring r is at least (r - 1) * cell away.
            if (r >= 1 && double(r - 1) * cell_ * double(r - 1) * cell_ > best2) break;
            for (int i = -r; i <= r; ++i)
                for (int j = -r; j <= r; ++j) {
                    const bool side = std::abs(i) == r || std::abs(j) == r;  // else only the ring's two caps in z
                    for (int k = -r; k <= r; k += side || r == 0 ? 1 : 2 * r) visit(c.offsetBy(i, j, k));
                }
        }
        return best2 < maxDist * maxDist ? std::sqrt(best2) : std::numeric_limits<double>::infinity();
    }

private:
    Coord cellOf(const Vec3d& p) const {
        return Coord(int(std::floor(p[0] / cell_)), int(std::floor(p[1] / cell_)), int(std::floor(p[2] / cell_)));
    }
    std::size_t indexOf(const Coord& d) const {
        return (std::size_t(d[2]) * std::size_t(dim_[1]) + std::size_t(d[1])) * std::size_t(dim_[0]) + std::size_t(d[0]);
    }
    std::vector<Vec3d> points_;
    double cell_;
    Coord lo_, dim_;
    std::vector<std::uint32_t> start_, order_;
};

/// Zero crossing of the distance grid `dist` (an accessor; none: no grid) between voxel centres a
/// and b (world), or the midpoint.
Vec3d crossing(const openvdb::FloatGrid::ConstAccessor* dist, const openvdb::math::Transform& xf, const Coord& a, const Coord& b) {
    const Vec3d pa = xf.indexToWorld(a), pb = xf.indexToWorld(b);
    if (dist) {
        const float fa = dist->getValue(a), fb = dist->getValue(b);
        if ((fa < 0) != (fb < 0) && fa != fb) {
            const double t = std::clamp(double(fa) / double(fa - fb), 0.0, 1.0);
            return pa + (pb - pa) * t;
        }
    }
    return (pa + pb) * 0.5;
}

double percentile(const std::vector<double>& sorted, double q) {
    if (sorted.empty()) return 0;
    const double pos = q * double(sorted.size() - 1);
    const std::size_t i = std::size_t(pos);
    const double f = pos - double(i);
    return i + 1 < sorted.size() ? sorted[i] * (1 - f) + sorted[i + 1] * f : sorted[i];
}

}  // namespace

void measureTooth(const LabelField& field, int unn, double capExclusionMm, ToothCarveSummary& out) {
    if (!field.labels) throw Error("measureTooth: label field without labels");
    const Label toothL = out.implant ? implantLabel(unn) : toothLabel(unn), pdlL = pdlLabel(unn), boneL = boneLabel(field.jaw);
    const auto& labels = *field.labels;
    const auto& xf = labels.transform();
    const double voxel = xf.voxelSize()[0];
    const double voxel3 = voxel * voxel * voxel;
    auto find = [&](Label l) -> const openvdb::FloatGrid* {
        const auto it = field.distances.find(l);
        return it == field.distances.end() ? nullptr : it->second.get();
    };
    const openvdb::FloatGrid* toothDist = find(toothL);
    const openvdb::FloatGrid* boneDist = find(boneL);

    // Where to look: the blocks (leaf-sized) of the box of the tooth's and PDL's distance grids,
    // or of the whole label grid when they are missing (a field edited by hand). A pass over the
    // whole jaw per tooth would cost more than the carving.
    using LeafT = openvdb::Int32Tree::LeafNodeType;
    const int dim = int(LeafT::DIM);
    CoordBBox box;
    const openvdb::FloatGrid* pdlDist = find(pdlL);
    if (toothDist && pdlDist) {
        box = toothDist->evalActiveVoxelBoundingBox();
        box.expand(pdlDist->evalActiveVoxelBoundingBox());
        // Interior tiles of the tooth lie inside its band's box; one block of margin for neighbours.
        box.expand(dim);
    } else {
        box = labels.evalActiveVoxelBoundingBox();
    }
    std::vector<Coord> blocks;
    if (!box.empty()) {
        const Coord lo = box.min() & ~(dim - 1);
        for (int x = lo.x(); x <= box.max().x(); x += dim)
            for (int y = lo.y(); y <= box.max().y(); y += dim)
                for (int z = lo.z(); z <= box.max().z(); z += dim) blocks.emplace_back(x, y, z);
    }

    // Volumes (tiles count their whole block) and interface points, collected per block and
    // concatenated in block order (deterministic).
    const std::size_t n = blocks.size();
    std::vector<std::vector<Vec3d>> toothSide(n), boneSide(n), openSide(n);
    std::vector<std::size_t> rootFaces(n, 0), toothFaces(n, 0), toothCount(n, 0), pdlCount(n, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
        auto acc = labels.getConstAccessor();
        std::optional<openvdb::FloatGrid::ConstAccessor> toothAcc, boneAcc;
        if (toothDist) toothAcc.emplace(toothDist->getConstAccessor());
        if (boneDist) boneAcc.emplace(boneDist->getConstAccessor());
        for (std::size_t li = r.begin(); li != r.end(); ++li) {
            const LeafT* leafPtr = acc.probeConstLeaf(blocks[li]);
            if (!leafPtr) {
                const Label l = acc.getValue(blocks[li]);
                if (acc.isValueOn(blocks[li]) && (l == toothL || l == pdlL))
                    (l == toothL ? toothCount : pdlCount)[li] += std::size_t(LeafT::SIZE);
                continue;
            }
            const auto& leaf = *leafPtr;
            for (auto v = leaf.cbeginValueOn(); v; ++v) {
                const Label l = *v;
                if (l != toothL && l != pdlL) continue;
                ++(l == toothL ? toothCount : pdlCount)[li];
                const Coord p = v.getCoord();
                for (const auto& d : kFace) {
                    const Coord q = p + d;
                    const Label m = acc.getValue(q);
                    if (l == toothL) {
                        if (m == toothL) continue;
                        ++toothFaces[li];
                        if (m == pdlL) {
                            ++rootFaces[li];
                            toothSide[li].push_back(crossing(toothAcc ? &*toothAcc : nullptr, xf, p, q));
                        }
                    } else if (m == boneL) {
                        boneSide[li].push_back(crossing(boneAcc ? &*boneAcc : nullptr, xf, q, p));
                    } else if (m != toothL && m != pdlL) {
                        openSide[li].push_back((xf.indexToWorld(p) + xf.indexToWorld(q)) * 0.5);
                    }
                }
            }
        }
    });
    auto flatten = [](std::vector<std::vector<Vec3d>>& parts) {
        std::vector<Vec3d> all;
        for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
        return all;
    };
    std::size_t rf = 0, tf = 0, toothVoxels = 0, pdlVoxels = 0;
    for (std::size_t i = 0; i < n; ++i)
        rf += rootFaces[i], tf += toothFaces[i], toothVoxels += toothCount[i], pdlVoxels += pdlCount[i];
    out.toothVolumeMm3 = double(toothVoxels) * voxel3;
    out.pdlVolumeMm3 = double(pdlVoxels) * voxel3;
    out.rootAreaFraction = tf ? double(rf) / double(tf) : 0.0;
    const auto toothPts = flatten(toothSide);
    const PointGrid bonePts(flatten(boneSide), 0.25);
    const PointGrid openPts(flatten(openSide), 0.25);
    out.impacted = pdlVoxels > 0 && openPts.empty();

    std::vector<double> t(toothPts.size(), -1.0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, toothPts.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            if (openPts.nearest(toothPts[i], capExclusionMm) < capExclusionMm) continue;
            const double d = bonePts.nearest(toothPts[i], 2.0);
            if (std::isfinite(d)) t[i] = d;
        }
    });
    t.erase(std::remove(t.begin(), t.end(), -1.0), t.end());
    std::sort(t.begin(), t.end());
    ThicknessStats s;
    s.samples = t.size();
    if (!t.empty()) {
        double sum = 0;
        for (double x : t) sum += x;
        s.min = t.front();
        s.max = t.back();
        s.mean = sum / double(t.size());
        s.p05 = percentile(t, 0.05);
        s.p95 = percentile(t, 0.95);
    }
    out.thickness = s;
}

}  // namespace jawmesh
