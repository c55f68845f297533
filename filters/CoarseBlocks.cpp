// Implements filters/CoarseBlocks.h; what it computes, its rules and its contract are documented there.
#include "filters/CoarseBlocks.h"

#include <algorithm>
#include <vector>

namespace jawmesh {
namespace {

using openvdb::Coord;

/// One label's voxels of the closed cube, n = size + 1 per side.
struct CubeMask {
    int n = 0;
    std::vector<char> in;  ///< 1 where the voxel has the first label
    char at(int x, int y, int z) const { return in[std::size_t((z * n + y) * n + x)]; }
};

/// Label changes along the line of n voxels from `from` in direction `step` (unit axis vectors).
int changesAlong(const CubeMask& m, std::array<int, 3> from, const std::array<int, 3>& step) {
    int changes = 0;
    char previous = m.at(from[0], from[1], from[2]);
    for (int i = 1; i < m.n; ++i) {
        for (int k = 0; k < 3; ++k) from[std::size_t(k)] += step[std::size_t(k)];
        const char here = m.at(from[0], from[1], from[2]);
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

/// Number of 4-connected components of the voxels of value `value` in an n x n face grid.
int faceComponents(const std::vector<char>& face, int n, char value) {
    thread_local std::vector<char> seen;  // scratch: this runs millions of times
    thread_local std::vector<int> stack;
    seen.assign(face.size(), 0);
    int components = 0;
    for (int start = 0; start < n * n; ++start) {
        if (face[std::size_t(start)] != value || seen[std::size_t(start)]) continue;
        ++components;
        seen[std::size_t(start)] = 1;
        stack.assign(1, start);
        while (!stack.empty()) {
            const int i = stack.back();
            stack.pop_back();
            const int u = i % n, v = i / n;
            const int nb[4][2] = {{u - 1, v}, {u + 1, v}, {u, v - 1}, {u, v + 1}};
            for (const auto& q : nb) {
                if (q[0] < 0 || q[1] < 0 || q[0] >= n || q[1] >= n) continue;
                const int j = q[1] * n + q[0];
                if (face[std::size_t(j)] == value && !seen[std::size_t(j)]) {
                    seen[std::size_t(j)] = 1;
                    stack.push_back(j);
                }
            }
        }
    }
    return components;
}

/// Each face: at most two changes around its border, each label one 4-connected piece.
bool facesCrossedInOneArc(const CubeMask& m) {
    const int n = m.n, e = n - 1;
    thread_local std::vector<char> face, ring;  // scratch
    face.resize(std::size_t(n * n));
    for (int axis = 0; axis < 3; ++axis)
        for (int side : {0, e}) {
            for (int v = 0; v < n; ++v)
                for (int u = 0; u < n; ++u) {
                    std::array<int, 3> p{};
                    p[std::size_t(axis)] = side;
                    p[std::size_t((axis + 1) % 3)] = u;
                    p[std::size_t((axis + 2) % 3)] = v;
                    face[std::size_t(v * n + u)] = m.at(p[0], p[1], p[2]);
                }
            // the border, walked once around
            ring.clear();
            for (int u = 0; u < e; ++u) ring.push_back(face[std::size_t(u)]);
            for (int v = 0; v < e; ++v) ring.push_back(face[std::size_t(v * n + e)]);
            for (int u = e; u > 0; --u) ring.push_back(face[std::size_t(e * n + u)]);
            for (int v = e; v > 0; --v) ring.push_back(face[std::size_t(v * n)]);
            int changes = 0;
            for (std::size_t i = 0; i < ring.size(); ++i) changes += ring[i] != ring[(i + 1) % ring.size()];
            if (changes > 2) return false;
            if (faceComponents(face, n, 0) > 1 || faceComponents(face, n, 1) > 1) return false;
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

/// One 6-connected component with Euler characteristic 1 (vertices - edges + squares - cubes of the
/// voxel complex): a ball. On a copy padded by one empty layer on every side, so that neighbours
/// need no bounds checks (this test was an eighth of the extraction's time).
bool isBall(const CubeMask& m, char value) {
    const int n = m.n, s = n + 2;
    const int dy = s, dz = s * s;
    thread_local std::vector<char> p;      // scratch
    thread_local std::vector<int> stack;
    p.assign(std::size_t(s * s * s), 0);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) p[std::size_t((z + 1) * dz + (y + 1) * dy + x + 1)] = m.at(x, y, z) == value;
    long chi = 0;
    int first = -1, count = 0;
    for (int z = 1; z <= n; ++z)
        for (int y = 1; y <= n; ++y)
            for (int i = z * dz + y * dy + 1, end = i + n; i < end; ++i) {
                if (!p[std::size_t(i)]) continue;
                if (first < 0) first = i;
                ++count;
                const auto at = [&](int offset) { return int(p[std::size_t(i + offset)]); };
                const int X = at(1), Y = at(dy), Z = at(dz);
                const int XY = X & Y & at(1 + dy), XZ = X & Z & at(1 + dz), YZ = Y & Z & at(dy + dz);
                chi += 1 - X - Y - Z + XY + XZ + YZ - (XY & XZ & YZ & at(1 + dy + dz));
            }
    if (first < 0 || chi != 1) return false;
    stack.assign(1, first);
    p[std::size_t(first)] = 0;  // reached voxels are cleared
    int reached = 0;
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        ++reached;
        for (const int offset : {-1, 1, -dy, dy, -dz, dz})
            if (p[std::size_t(i + offset)]) {
                p[std::size_t(i + offset)] = 0;
                stack.push_back(i + offset);
            }
    }
    return reached == count;
}

/// The disc tests of the header on a two-valued mask.
bool maskIsOneDisc(const CubeMask& m) {
    return edgesCrossedAtMostOnce(m) && cornersFormOneLoop(m) && facesCrossedInOneArc(m) && isBall(m, 0) && isBall(m, 1);
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
    m.in.resize(cube.size());
    for (std::size_t i = 0; i < cube.size(); ++i) m.in[i] = cube[i] == value;
    return m;
}

/// Mask m grown by r voxels in every direction (the Chebyshev ball: separable, one axis at a time).
CubeMask grown(CubeMask m, int r) {
    const int n = m.n;
    for (int axis = 0; axis < 3; ++axis) {
        const int stride = axis == 0 ? 1 : axis == 1 ? n : n * n;
        std::vector<char> next(m.in.size(), 0);
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const int i = (z * n + y) * n + x, along = axis == 0 ? x : axis == 1 ? y : z;
                    if (!m.in[std::size_t(i)]) continue;
                    for (int d = std::max(-r, -along); d <= std::min(r, n - 1 - along); ++d) next[std::size_t(i + d * stride)] = 1;
                }
        m.in = std::move(next);
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
    thread_local std::vector<Label> cube, found;  // scratch
    if (!cubeLabels(labels, lo, n, 2, cube, found) || found.size() != 2) return std::nullopt;
    const Label a = found[0], b = found[1];
    if (!allowed(std::min(a, b), std::max(a, b)) || !maskIsOneDisc(maskOf(cube, n, a))) return std::nullopt;
    return std::array<Label, 2>{std::min(a, b), std::max(a, b)};
}

std::optional<BlockLayer> blockIsLayer(const LabelWindow& labels, const Coord& lo, int size,
                                       int minGapVoxels) {
    const int n = size + 1;
    thread_local std::vector<Label> cube, found;  // scratch
    if (!cubeLabels(labels, lo, n, 3, cube, found) || found.size() != 3) return std::nullopt;
    std::sort(found.begin(), found.end());
    const CubeMask masks[3] = {maskOf(cube, n, found[0]), maskOf(cube, n, found[1]), maskOf(cube, n, found[2])};
    // the outer pair: the two labels with minGapVoxels of the third between them everywhere
    for (int middle = 0; middle < 3; ++middle) {
        const int a = (middle + 1) % 3, c = (middle + 2) % 3;
        const CubeMask near = grown(masks[a], minGapVoxels);
        bool apart = true;
        for (std::size_t i = 0; i < cube.size() && apart; ++i) apart = !(near.in[i] && masks[c].in[i]);
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
