// Implements filters/CoarseBlocks.h; what it computes, its rules and its contract are documented there.
#include "filters/CoarseBlocks.h"

#include "io/Error.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace jawmesh {
namespace {

using openvdb::Coord;

/// One label's voxels of the closed cube, n = size + 1 <= 64 per side, as bit rows: bit x of
/// row z * n + y is set where voxel (x, y, z) has the label. The tests below then take whole rows
/// at a time (per voxel they were a fifth of the extraction on the shared mandible).
struct CubeMask {
    int n = 0;
    std::vector<std::uint64_t> rows;
    std::uint64_t row(int y, int z) const { return rows[std::size_t(z * n + y)]; }
    bool at(int x, int y, int z) const { return (row(y, z) >> x) & 1u; }
    std::uint64_t full() const { return n == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << n) - 1; }
};

inline int popcount(std::uint64_t x) { return __builtin_popcountll(x); }

/// Label changes along the line of n voxels from `from` in direction `step` (unit axis vectors).
int changesAlong(const CubeMask& m, std::array<int, 3> from, const std::array<int, 3>& step) {
    if (step[0] == 1) {  // along a row: the bits that differ from their neighbour
        const std::uint64_t r = m.row(from[1], from[2]);
        return popcount((r ^ (r >> 1)) & (m.full() >> 1));
    }
    int changes = 0;
    bool previous = m.at(from[0], from[1], from[2]);
    for (int i = 1; i < m.n; ++i) {
        for (int k = 0; k < 3; ++k) from[std::size_t(k)] += step[std::size_t(k)];
        const bool here = m.at(from[0], from[1], from[2]);
        changes += here != previous;
        previous = here;
    }
    return changes;
}

bool edgesCrossedAtMostOnce(const CubeMask& m) {
    const int e = m.n - 1;
    for (int axis = 0; axis < 3; ++axis)
        for (int a : {0, e})
            for (int b : {0, e}) {
                std::array<int, 3> from{}, step{};
                from[std::size_t((axis + 1) % 3)] = a;
                from[std::size_t((axis + 2) % 3)] = b;
                step[std::size_t(axis)] = 1;
                if (changesAlong(m, from, step) > 1) return false;
            }
    return true;
}

/// Minimal union-find over small integer ids (the runs of a mask).
struct Components {
    std::vector<int> parent;
    int count = 0;
    void clear() {
        parent.clear();
        count = 0;
    }
    int add() {
        parent.push_back(int(parent.size()));
        ++count;
        return parent.back();
    }
    int find(int i) {
        while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
        return i;
    }
    void join(int a, int b) {
        a = find(a);
        b = find(b);
        if (a == b) return;
        parent[std::size_t(std::max(a, b))] = std::min(a, b);
        --count;
    }
};

/// A maximal run of set bits of one row and its union-find id.
struct Run {
    std::uint64_t bits;
    int id;
};

/// The runs of `row`, appended to `out` with fresh ids.
void appendRuns(std::uint64_t row, Components& uf, std::vector<Run>& out) {
    while (row) {
        const std::uint64_t low = row & (~row + 1);        // lowest set bit
        const std::uint64_t run = ((row + low) ^ row) & row;  // it and the set bits above it in a row
        out.push_back({run, uf.add()});
        row &= ~run;
    }
}

/// Joins the runs [a, a + na) with the overlapping ones of [b, b + nb) (4/6-adjacent rows).
void joinOverlapping(const Run* a, std::size_t na, const Run* b, std::size_t nb, Components& uf) {
    for (std::size_t i = 0; i < na; ++i)
        for (std::size_t j = 0; j < nb; ++j)
            if (a[i].bits & b[j].bits) uf.join(a[i].id, b[j].id);
}

/// Number of connected components of the set bits of `rows`: `layers` layers of n rows each (row
/// y of layer z at z * n + y), a bit joined to its neighbours in its row, in the rows beside it in
/// its layer and in the same row of the layers beside it (a face: one layer, 4-connected; a cube:
/// n layers, 6-connected). Runs of bits are joined across rows.
int rowComponents(const std::vector<std::uint64_t>& rows, int n, int layers) {
    thread_local Components uf;  // scratch: this runs millions of times
    thread_local std::vector<Run> runs;
    thread_local std::vector<std::size_t> start;
    uf.clear();
    runs.clear();
    start.assign(1, 0);
    for (int z = 0; z < layers; ++z)
        for (int y = 0; y < n; ++y) {
            const std::size_t i = std::size_t(z * n + y);
            appendRuns(rows[i], uf, runs);
            start.push_back(runs.size());
            const auto join = [&](std::size_t j) {
                joinOverlapping(&runs[start[i]], start[i + 1] - start[i], &runs[start[j]], start[j + 1] - start[j], uf);
            };
            if (y > 0) join(i - 1);
            if (z > 0) join(i - std::size_t(n));
        }
    return uf.count;
}

/// `rows` with every bit of the n-bit rows flipped: the other label's mask.
std::vector<std::uint64_t>& complement(std::vector<std::uint64_t>& rows, const CubeMask& m) {
    for (std::uint64_t& r : rows) r = ~r & m.full();
    return rows;
}

/// Face `side` (0 or n - 1) across `axis` as n rows of n bits (any fixed layout: the tests below
/// do not depend on the face's orientation).
void faceRows(const CubeMask& m, int axis, int side, std::vector<std::uint64_t>& face) {
    const int n = m.n;
    face.assign(std::size_t(n), 0);
    for (int v = 0; v < n; ++v)
        for (int u = 0; u < n; ++u) {
            const bool bit = axis == 0 ? m.at(side, u, v) : axis == 1 ? m.at(v, side, u) : m.at(u, v, side);
            face[std::size_t(v)] |= std::uint64_t(bit) << u;
        }
}

/// Each face: at most two changes around its border, each label one 4-connected piece.
bool facesCrossedInOneArc(const CubeMask& m) {
    const int n = m.n, e = n - 1;
    thread_local std::vector<std::uint64_t> face, other;  // scratch
    thread_local std::vector<char> ring;
    for (int axis = 0; axis < 3; ++axis)
        for (int side : {0, e}) {
            faceRows(m, axis, side, face);
            const auto at = [&](int u, int v) { return char((face[std::size_t(v)] >> u) & 1u); };
            // the border, walked once around
            ring.clear();
            for (int u = 0; u < e; ++u) ring.push_back(at(u, 0));
            for (int v = 0; v < e; ++v) ring.push_back(at(e, v));
            for (int u = e; u > 0; --u) ring.push_back(at(u, e));
            for (int v = e; v > 0; --v) ring.push_back(at(0, v));
            int changes = 0;
            for (std::size_t i = 0; i < ring.size(); ++i) changes += ring[i] != ring[(i + 1) % ring.size()];
            if (changes > 2) return false;
            other = face;
            if (rowComponents(face, n, 1) > 1 || rowComponents(complement(other, m), n, 1) > 1) return false;
        }
    return true;
}

/// Both labels among the 8 corners, each label's corners connected along the cube's edges.
bool cornersFormOneLoop(const CubeMask& m) {
    const int e = m.n - 1;
    char corner[8];
    for (int k = 0; k < 8; ++k) corner[k] = m.at(k & 1 ? e : 0, k & 2 ? e : 0, k & 4 ? e : 0);
    for (char value : {char(0), char(1)}) {
        int first = -1, members = 0;
        for (int k = 0; k < 8; ++k)
            if (corner[k] == value) {
                ++members;
                if (first < 0) first = k;
            }
        if (members == 0) return false;
        int reached = 1 << first, previous = 0;
        while (reached != previous) {
            previous = reached;
            for (int k = 0; k < 8; ++k)
                if (reached & (1 << k))
                    for (int bit : {1, 2, 4})
                        if (corner[k ^ bit] == value) reached |= 1 << (k ^ bit);
        }
        int count = 0;
        for (int k = 0; k < 8; ++k) count += (reached >> k) & 1;
        if (count != members) return false;
    }
    return true;
}

// The Euler characteristic is popcounts; built for the baseline x86-64 they are library calls
// (a third of the block tests), so it is also built with the POPCNT instruction, chosen at load
// time where the processor has it.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define JAWMESH_POPCNT_CLONES __attribute__((target_clones("popcnt", "default")))
#else
#define JAWMESH_POPCNT_CLONES
#endif

/// Euler characteristic of the voxel complex of `rows` (n x n rows): vertices - edges + squares -
/// cubes, each counted at its lowest corner with whole-row bit operations.
JAWMESH_POPCNT_CLONES long eulerCharacteristic(const std::vector<std::uint64_t>& rows, int n) {
    const auto r = [&](int y, int z) { return y < n && z < n ? rows[std::size_t(z * n + y)] : std::uint64_t(0); };
    long chi = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y) {
            const std::uint64_t a = r(y, z), ay = r(y + 1, z), az = r(y, z + 1), ayz = r(y + 1, z + 1);
            const std::uint64_t xy = a & ay, xz = a & az, yzSquare = xy & az & ayz;
            chi += popcount(a) - popcount(a & (a >> 1)) - popcount(xy) - popcount(xz);
            chi += popcount(xy & (xy >> 1)) + popcount(xz & (xz >> 1)) + popcount(yzSquare);
            chi -= popcount(yzSquare & (yzSquare >> 1));
        }
    return chi;
}

/// One 6-connected component with Euler characteristic 1: a ball.
bool isBall(const CubeMask& m, bool value) {
    thread_local std::vector<std::uint64_t> rows;  // scratch
    rows = m.rows;
    if (!value) complement(rows, m);
    return eulerCharacteristic(rows, m.n) == 1 && rowComponents(rows, m.n, m.n) == 1;
}

/// The disc tests of the header on a two-valued mask.
bool maskIsOneDisc(const CubeMask& m) {
    return edgesCrossedAtMostOnce(m) && cornersFormOneLoop(m) && facesCrossedInOneArc(m) && isBall(m, false) &&
           isBall(m, true);
}

/// The labels of the closed cube [lo, lo + size]^3 (n = size + 1 per side), x fastest; up to
/// `most` distinct labels in `found` (first seen first); false when there are more.
bool cubeLabels(const LabelWindow& labels, const Coord& lo, int n, std::size_t most,
                std::vector<Label>& cube, std::vector<Label>& found) {
    cube.resize(std::size_t(n * n * n));
    found.clear();
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const Label l = labels.at(lo.offsetBy(x, y, z));
                cube[std::size_t((z * n + y) * n + x)] = l;
                if (std::find(found.begin(), found.end(), l) == found.end()) {
                    if (found.size() == most) return false;
                    found.push_back(l);
                }
            }
    return true;
}

CubeMask maskOf(const std::vector<Label>& cube, int n, Label value) {
    CubeMask m;
    m.n = n;
    m.rows.assign(std::size_t(n * n), 0);
    for (std::size_t r = 0; r < m.rows.size(); ++r)
        for (int x = 0; x < n; ++x) m.rows[r] |= std::uint64_t(cube[r * std::size_t(n) + std::size_t(x)] == value) << x;
    return m;
}

/// Mask m grown by r voxels in every direction (the Chebyshev ball: separable, one axis at a time).
CubeMask grown(CubeMask m, int r) {
    const int n = m.n;
    for (std::uint64_t& row : m.rows) {
        std::uint64_t g = row;
        for (int d = 1; d <= r && d < n; ++d) g |= (row << d) | (row >> d);
        row = g & m.full();
    }
    for (int axis = 1; axis <= 2; ++axis) {
        std::vector<std::uint64_t> next(m.rows.size(), 0);
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y) {
                const int along = axis == 1 ? y : z;
                for (int d = std::max(-r, -along); d <= std::min(r, n - 1 - along); ++d)
                    next[std::size_t(z * n + y)] |= axis == 1 ? m.row(y + d, z) : m.row(y, z + d);
            }
        m.rows = std::move(next);
    }
    return m;
}

}  // namespace

LabelWindow::LabelWindow(const openvdb::Int32Grid::ConstAccessor& labels, const Coord& lo, int n)
    : labels_(labels), lo_(lo), n_(n), dense_(std::size_t(n * n * n)) {
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) dense_[std::size_t((z * n + y) * n + x)] = labels.getValue(lo.offsetBy(x, y, z));
}

std::optional<std::array<Label, 2>> blockIsOneDisc(const LabelWindow& labels, const Coord& lo,
                                                   int size, const std::function<bool(Label, Label)>& allowed) {
    const int n = size + 1;
    if (n > 64) throw Error("adaptive surface: a block of more than 63 voxels across");
    thread_local std::vector<Label> cube, found;  // scratch
    if (!cubeLabels(labels, lo, n, 2, cube, found) || found.size() != 2) return std::nullopt;
    const Label a = found[0], b = found[1];
    if (!allowed(std::min(a, b), std::max(a, b)) || !maskIsOneDisc(maskOf(cube, n, a))) return std::nullopt;
    return std::array<Label, 2>{std::min(a, b), std::max(a, b)};
}

std::optional<BlockLayer> blockIsLayer(const LabelWindow& labels, const Coord& lo, int size,
                                       int minGapVoxels) {
    const int n = size + 1;
    if (n > 64) throw Error("adaptive surface: a block of more than 63 voxels across");
    thread_local std::vector<Label> cube, found;  // scratch
    if (!cubeLabels(labels, lo, n, 3, cube, found) || found.size() != 3) return std::nullopt;
    std::sort(found.begin(), found.end());
    const CubeMask masks[3] = {maskOf(cube, n, found[0]), maskOf(cube, n, found[1]), maskOf(cube, n, found[2])};
    // the outer pair: the two labels with minGapVoxels of the third between them everywhere
    for (int middle = 0; middle < 3; ++middle) {
        const int a = (middle + 1) % 3, c = (middle + 2) % 3;
        const CubeMask near = grown(masks[a], minGapVoxels);
        bool apart = true;
        for (std::size_t i = 0; i < near.rows.size() && apart; ++i) apart = !(near.rows[i] & masks[c].rows[i]);
        if (!apart) continue;
        if (!maskIsOneDisc(masks[a]) || !maskIsOneDisc(masks[c])) return std::nullopt;
        BlockLayer layer;
        layer.middle = found[std::size_t(middle)];
        layer.outer = {std::min(found[std::size_t(a)], found[std::size_t(c)]), std::max(found[std::size_t(a)], found[std::size_t(c)])};
        return layer;
    }
    return std::nullopt;
}

}  // namespace jawmesh
