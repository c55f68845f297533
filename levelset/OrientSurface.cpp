// Implements levelset/OrientSurface.h; what it computes, its rules and its contract are documented there.
#include "levelset/OrientSurface.h"

#include "levelset/LineWinding.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <numeric>

namespace jawmesh {

namespace {
using Index = std::int32_t;

bool lessPosition(const Vec3& a, const Vec3& b) {
    if (a.x() != b.x()) return a.x() < b.x();
    if (a.y() != b.y()) return a.y() < b.y();
    return a.z() < b.z();
}

// Merges bitwise-equal positions; returns the new index of every input vertex.
std::vector<Index> weldVertices(const std::vector<Vec3>& in, std::vector<Vec3>& out) {
    std::vector<Index> order(in.size());
    std::iota(order.begin(), order.end(), 0);
    tbb::parallel_sort(order.begin(), order.end(), [&](Index a, Index b) {
        const Vec3& pa = in[static_cast<std::size_t>(a)];
        const Vec3& pb = in[static_cast<std::size_t>(b)];
        if (lessPosition(pa, pb)) return true;
        if (lessPosition(pb, pa)) return false;
        return a < b;
    });
    std::vector<Index> remap(in.size());
    out.clear();
    for (std::size_t i = 0; i < order.size(); ++i) {
        const Vec3& p = in[static_cast<std::size_t>(order[i])];
        if (i == 0 || p != in[static_cast<std::size_t>(order[i - 1])]) out.push_back(p);
        remap[static_cast<std::size_t>(order[i])] = static_cast<Index>(out.size() - 1);
    }
    return remap;
}

struct HalfEdge {
    std::uint64_t key;  // (min vertex << 32) | max vertex
    Index tri;
    std::int8_t corner;
    bool forward;  // the triangle walks the edge from min to max
};

struct PatchSummary {
    double keptArea = 0.0;     // area of triangles whose input orientation survives
    double flippedArea = 0.0;  // area of triangles that the consistent orientation reverses
    Index largest = -1;
    double largestArea = -1.0;
    Index size = 0;
};

double triangleArea(const std::vector<Vec3>& v, const Tri& t) {
    return 0.5 * (v[static_cast<std::size_t>(t[1])] - v[static_cast<std::size_t>(t[0])])
                     .cross(v[static_cast<std::size_t>(t[2])] - v[static_cast<std::size_t>(t[0])])
                     .norm();
}
/// Welded, without degenerate triangles, then without duplicates (same vertex set; the first one
/// is kept); counts what it drops in out. Each triangle's tests and sorted key are made once, in
/// parallel (keys remade in every comparison of the sort were 1.6 s of the shared mandible's bone).
void cleanTriangles(const SurfaceMesh& mesh, const std::vector<Index>& remap, OrientedSurface& out) {
    const BBox box = boundingBox(mesh);
    const double scale = box.empty() ? 1.0 : std::max(box.size().maxCoeff(), 1e-9);
    const double minDoubleArea = 1e-14 * scale * scale;
    const std::size_t n = mesh.triangles.size();
    std::vector<Tri> welded(n);
    std::vector<char> degenerate(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            const Tri& f = mesh.triangles[t];
            const Tri w = {remap[static_cast<std::size_t>(f[0])], remap[static_cast<std::size_t>(f[1])],
                           remap[static_cast<std::size_t>(f[2])]};
            welded[t] = w;
            degenerate[t] = w[0] == w[1] || w[1] == w[2] || w[0] == w[2] || 2.0 * triangleArea(out.vertices, w) <= minDoubleArea;
        }
    });
    std::vector<Tri> tris;
    tris.reserve(n);
    for (std::size_t t = 0; t < n; ++t) {
        if (degenerate[t]) ++out.droppedDegenerate;
        else tris.push_back(welded[t]);
    }
    std::vector<Tri>().swap(welded);
    // (sorted corners, index): equal vertex sets side by side, the first triangle first
    std::vector<std::pair<Tri, Index>> keyed(tris.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tris.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            Tri k = tris[i];
            std::sort(k.begin(), k.end());
            keyed[i] = {k, static_cast<Index>(i)};
        }
    });
    tbb::parallel_sort(keyed.begin(), keyed.end());
    std::vector<char> keep(tris.size(), 1);
    for (std::size_t i = 1; i < keyed.size(); ++i)
        if (keyed[i].first == keyed[i - 1].first) keep[static_cast<std::size_t>(keyed[i].second)] = 0;
    for (std::size_t i = 0; i < tris.size(); ++i) {
        if (keep[i]) out.triangles.push_back(tris[i]);
        else ++out.droppedDuplicate;
    }
}

/// Manifold adjacency: an edge with exactly two triangles links them. neighbour[3t+c] = the
/// triangle across edge c of t (or -1); sameWalk[3t+c]: both walk that edge the same way.
void manifoldNeighbours(const std::vector<Tri>& triangles, std::vector<Index>& neighbour, std::vector<char>& sameWalk) {
    const std::size_t n = triangles.size();
    std::vector<HalfEdge> edges(3 * n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t t) {
        for (int c = 0; c < 3; ++c) {
            const std::int32_t a = triangles[t][c], b = triangles[t][(c + 1) % 3];
            edges[3 * t + c] = {edgeKey(a, b), static_cast<Index>(t), static_cast<std::int8_t>(c), a < b};
        }
    });
    tbb::parallel_sort(edges.begin(), edges.end(), [](const HalfEdge& a, const HalfEdge& b) {
        return a.key < b.key || (a.key == b.key && (a.tri < b.tri || (a.tri == b.tri && a.corner < b.corner)));
    });
    neighbour.assign(3 * n, -1);
    sameWalk.assign(3 * n, 0);
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j].key == edges[i].key) ++j;
        if (j - i == 2 && edges[i].tri != edges[i + 1].tri) {
            const HalfEdge& a = edges[i];
            const HalfEdge& b = edges[i + 1];
            neighbour[3 * static_cast<std::size_t>(a.tri) + a.corner] = b.tri;
            neighbour[3 * static_cast<std::size_t>(b.tri) + b.corner] = a.tri;
            sameWalk[3 * static_cast<std::size_t>(a.tri) + a.corner] = a.forward == b.forward;
            sameWalk[3 * static_cast<std::size_t>(b.tri) + b.corner] = a.forward == b.forward;
        }
        i = j;
    }
}

/// Breadth-first propagation of a flip flag through manifold edges, patch by patch (out.patch);
/// then each patch takes the majority of its input orientation, by area.
std::vector<PatchSummary> propagateOrientation(OrientedSurface& out, const std::vector<Index>& neighbour,
                                               const std::vector<char>& sameWalk, std::vector<char>& flip) {
    const std::size_t n = out.triangles.size();
    out.patch.assign(n, -1);
    flip.assign(n, 0);
    std::vector<PatchSummary> summary;
    std::deque<Index> queue;
    for (std::size_t seed = 0; seed < n; ++seed) {
        if (out.patch[seed] >= 0) continue;
        const Index id = static_cast<Index>(summary.size());
        summary.emplace_back();
        out.patch[seed] = id;
        queue.push_back(static_cast<Index>(seed));
        while (!queue.empty()) {
            const auto t = static_cast<std::size_t>(queue.front());
            queue.pop_front();
            PatchSummary& s = summary.back();
            const double area = triangleArea(out.vertices, out.triangles[t]);
            (flip[t] ? s.flippedArea : s.keptArea) += area;
            if (area > s.largestArea) {
                s.largestArea = area;
                s.largest = static_cast<Index>(t);
            }
            ++s.size;
            for (int c = 0; c < 3; ++c) {
                const Index nb = neighbour[3 * t + c];
                if (nb < 0 || out.patch[static_cast<std::size_t>(nb)] >= 0) continue;
                out.patch[static_cast<std::size_t>(nb)] = id;
                flip[static_cast<std::size_t>(nb)] = sameWalk[3 * t + c] ? !flip[t] : flip[t];
                queue.push_back(nb);
            }
        }
    }
    std::vector<char> invertPatch(summary.size(), 0);
    for (std::size_t p = 0; p < summary.size(); ++p) invertPatch[p] = summary[p].flippedArea > summary[p].keptArea;
    for (std::size_t t = 0; t < n; ++t)
        if (invertPatch[static_cast<std::size_t>(out.patch[t])]) flip[t] = !flip[t];
    return summary;
}

/// Which patches lie inside others (judged with the majority orientation of the others).
std::vector<char> nestedPatches(const OrientedSurface& out, const std::vector<PatchSummary>& summary, const std::vector<char>& flip) {
    std::vector<char> nested(summary.size(), 0);
    constexpr Index kMinPatchForNesting = 16;
    if (summary.size() <= 1) return nested;
    const std::size_t n = out.triangles.size();
    LineWindingQuery query(out.vertices, out.triangles, out.patch);
    std::vector<std::int8_t> sign(n);
    for (std::size_t t = 0; t < n; ++t) sign[t] = flip[t] ? -1 : 1;
    query.setOrientation(std::move(sign));
    tbb::parallel_for(std::size_t(0), summary.size(), [&](std::size_t p) {
        if (summary[p].size < kMinPatchForNesting) return;
        const Tri& t = out.triangles[static_cast<std::size_t>(summary[p].largest)];
        const Vec3 q = (out.vertices[static_cast<std::size_t>(t[0])] + out.vertices[static_cast<std::size_t>(t[1])] +
                        out.vertices[static_cast<std::size_t>(t[2])]) / 3.0;
        int inside = 0, outside = 0;
        for (int k = 0; k < 7 && inside < 3 && outside < 3; ++k) {
            const auto w = query.windingAlongLine(q, LineWindingQuery::genericDirection(k), static_cast<Index>(p));
            if (!w) continue;
            (*w != 0 ? inside : outside) += 1;
        }
        nested[p] = inside > outside;
    });
    return nested;
}

/// Signed volume (times 6) of each patch about its own box centre, with the flips applied.
std::vector<double> patchVolumes(const OrientedSurface& out, std::size_t patches, const std::vector<char>& flip) {
    const std::size_t n = out.triangles.size();
    std::vector<Vec3> centre(patches, Vec3::Zero());
    std::vector<BBox> boxes(patches);
    for (std::size_t t = 0; t < n; ++t)
        for (Index v : out.triangles[t]) boxes[static_cast<std::size_t>(out.patch[t])].extend(out.vertices[static_cast<std::size_t>(v)]);
    for (std::size_t p = 0; p < patches; ++p) centre[p] = 0.5 * (boxes[p].min + boxes[p].max);
    std::vector<double> volume(patches, 0.0);
    for (std::size_t t = 0; t < n; ++t) {
        const auto p = static_cast<std::size_t>(out.patch[t]);
        const Tri& tri = out.triangles[t];
        const Vec3 a = out.vertices[static_cast<std::size_t>(tri[0])] - centre[p];
        const Vec3 b = out.vertices[static_cast<std::size_t>(tri[1])] - centre[p];
        const Vec3 c = out.vertices[static_cast<std::size_t>(tri[2])] - centre[p];
        volume[p] += (flip[t] ? -1.0 : 1.0) * a.dot(b.cross(c));
    }
    return volume;
}

}  // namespace

OrientedSurface orientSurface(const SurfaceMesh& mesh, Progress& progress) {
    OrientedSurface out;
    const std::vector<Index> remap = weldVertices(mesh.vertices, out.vertices);
    progress.checkCancelled();
    cleanTriangles(mesh, remap, out);
    progress.checkCancelled();
    std::vector<Index> neighbour;
    std::vector<char> sameWalk, flip;
    manifoldNeighbours(out.triangles, neighbour, sameWalk);
    progress.checkCancelled();
    const std::vector<PatchSummary> summary = propagateOrientation(out, neighbour, sameWalk, flip);
    out.patchCount = static_cast<int>(summary.size());
    progress.checkCancelled();
    const std::vector<char> nested = nestedPatches(out, summary, flip);
    progress.checkCancelled();
    // Outermost patches point outward: positive signed volume about the patch's own centre.
    const std::vector<double> volume = patchVolumes(out, summary.size(), flip);
    std::vector<char> invertPatch(summary.size(), 0);
    for (std::size_t p = 0; p < summary.size(); ++p) {
        if (nested[p]) ++out.nestedPatches;
        invertPatch[p] = !nested[p] && volume[p] < 0.0;
    }
    for (std::size_t t = 0; t < out.triangles.size(); ++t) {
        if (invertPatch[static_cast<std::size_t>(out.patch[t])]) flip[t] = !flip[t];
        if (flip[t]) {
            std::swap(out.triangles[t][1], out.triangles[t][2]);
            ++out.flipped;
        }
    }
    return out;
}

}  // namespace jawmesh
