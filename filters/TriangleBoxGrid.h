// A uniform grid of triangle bounding boxes for "which triangles may meet this box" queries on a
// mesh that changes as it is queried (the simplification moves and deletes triangles).
#pragma once

#include "io/SurfaceMesh.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace jawmesh {

/// Uniform grid of triangle boxes: a triangle is listed in every cell its box meets (cells of a
/// few fine triangles, so queries stay local). Entries carry the triangle's version; moving or
/// deleting a triangle bumps it, so stale entries are skipped without searching the cells.
class TriangleBoxGrid {
public:
    /// cellMm: the edge of a cell, mm.
    explicit TriangleBoxGrid(double cellMm) : cell_(cellMm) {}

    /// Lists triangle t (any id >= 0) in the cells `box` meets; its earlier entries become stale.
    void place(std::int32_t t, const BBox& box) {
        if (std::size_t(t) >= version_.size()) {
            version_.resize(std::size_t(t) + 1, 0);
            seen_.resize(std::size_t(t) + 1, 0);
        }
        const std::uint32_t ver = ++version_[std::size_t(t)];
        forCells(box, [&](std::uint64_t key) { cells_[key].push_back({t, ver}); });
    }

    /// Makes every entry of a placed triangle t stale.
    void remove(std::int32_t t) { ++version_[std::size_t(t)]; }

    /// Calls f(t) once for every live triangle listed in a cell that `box` meets (and drops the
    /// stale entries met on the way).
    template <typename F>
    void query(const BBox& box, F&& f) {
        ++queryId_;
        forCells(box, [&](std::uint64_t key) {
            const auto it = cells_.find(key);
            if (it == cells_.end()) return;
            auto& entries = it->second;
            std::size_t keep = 0;
            for (std::size_t i = 0; i < entries.size(); ++i) {
                const Entry e = entries[i];
                if (version_[std::size_t(e.t)] != e.version) continue;  // stale: drop it
                entries[keep++] = e;
                if (seen_[std::size_t(e.t)] == queryId_) continue;
                seen_[std::size_t(e.t)] = queryId_;
                f(e.t);
            }
            entries.resize(keep);
        });
    }

private:
    struct Entry {
        std::int32_t t;
        std::uint32_t version;
    };
    template <typename F>
    void forCells(const BBox& box, F&& f) const {
        const auto c = [&](double x) { return int(std::floor(x / cell_)); };
        const int x0 = c(box.min.x()), x1 = c(box.max.x()), y0 = c(box.min.y()), y1 = c(box.max.y());
        const int z0 = c(box.min.z()), z1 = c(box.max.z());
        for (int x = x0; x <= x1; ++x)
            for (int y = y0; y <= y1; ++y)
                for (int z = z0; z <= z1; ++z) f(keyOf(x, y, z));
    }
    static std::uint64_t keyOf(int x, int y, int z) {
        const auto m = [](int v) { return std::uint64_t(std::uint32_t(v + (1 << 20)) & 0x1FFFFF); };
        return (m(x) << 42) | (m(y) << 21) | m(z);
    }
    double cell_;
    std::unordered_map<std::uint64_t, std::vector<Entry>> cells_;
    std::vector<std::uint32_t> version_;
    std::vector<std::uint32_t> seen_;
    std::uint32_t queryId_ = 0;
};

}  // namespace jawmesh
