// Implements filters/FillSurfaceHoles.h; what it computes, its rules and its contract are documented there.
#include "filters/FillSurfaceHoles.h"

#include "filters/HoleFlap.h"
#include "filters/HoleLoops.h"
#include "filters/PatchChecks.h"
#include "filters/PatchWedge.h"
#include "filters/TriangulateLoop.h"
#include "io/Labels.h"

#include <algorithm>
#include <functional>
#include <map>
#include <unordered_set>

namespace jawmesh {
namespace {

/// Drops the triangles marked in `removed`, and the vertices no triangle uses then.
void dropTriangles(InterfaceComplex& c, const std::vector<char>& removed) {
    std::vector<Tri> kept;
    std::vector<std::array<Label, 2>> sides;
    for (std::size_t t = 0; t < c.surface.triangles.size(); ++t)
        if (!removed[t]) {
            kept.push_back(c.surface.triangles[t]);
            sides.push_back(c.sides[t]);
        }
    c.surface = compactSurface(c.surface.vertices, std::move(kept));
    c.sides = std::move(sides);
}

/// Whether the sheet's triangles along the loop have sides {pair[1], pair[0]} (the loop's own
/// winding) rather than {pair[0], pair[1]} (the majority; the loop's winding on a tie).
bool sheetUsesLoopOrder(const InterfaceComplex& c, const HoleLoop& loop, const std::unordered_set<std::uint64_t>& loopEdges) {
    long vote = 0;
    for (std::size_t t = 0; t < c.surface.triangles.size(); ++t) {
        const Tri& tri = c.surface.triangles[t];
        const auto& sides = c.sides[t];
        if (std::min(sides[0], sides[1]) != loop.pair[0] || std::max(sides[0], sides[1]) != loop.pair[1]) continue;
        for (int k = 0; k < 3; ++k)
            if (loopEdges.count(edgeKey(tri[std::size_t(k)], tri[std::size_t((k + 1) % 3)]))) {
                vote += sides[0] == loop.pair[1] ? 1 : -1;
                break;
            }
    }
    return vote >= 0;
}

/// A candidate patch of one loop, its triangles wound as the loop (global indices, its new points
/// appended after the surface's vertices).
struct Candidate {
    std::vector<Tri> triangles;
    std::vector<Vec3> apex;
    HoleRepair how;
};

/// Of clean candidate patches of one loop, the first when its smallest wedge (firstDeg) reaches
/// kHoleMinWedgeDeg; else the one with the widest smallest wedge among those that sweep over no
/// vertex or seed on their way from the first (filters/PatchChecks.h).
std::size_t widestWedge(const InterfaceComplex& c, const HoleLoop& loop, const std::vector<std::int32_t>& near,
                        const std::vector<Candidate>& clean, double firstDeg, const std::function<double(const Candidate&)>& wedgeDeg) {
    std::size_t best = 0;
    double bestDeg = firstDeg;
    if (bestDeg >= kHoleMinWedgeDeg) return best;
    const Candidate& first = clean.front();
    for (std::size_t i = 1; i < clean.size(); ++i) {
        const double deg = wedgeDeg(clean[i]);
        if (deg > bestDeg && !patchSweepsAVertex(c.surface, near, loop.vertices, first.triangles, first.apex, clean[i].triangles,
                                                 clean[i].apex, c.seeds)) {
            best = i;
            bestDeg = deg;
        }
    }
    return best;
}

/// One loop: the patch (global indices, apex appended after the surface's vertices) or empty. The
/// first clean of ear clipping, least area and a centroid fan; when that one opens a region wedge
/// under kHoleMinWedgeDeg (filters/PatchWedge.h), the clean candidate with the widest smallest
/// wedge among those and fans whose apex is raised or sunk along the loop's normal, provided it
/// sweeps over no vertex on its way from the first (filters/PatchChecks.h).
std::vector<Tri> patchFor(const InterfaceComplex& c, const HoleLoop& loop, const std::unordered_set<std::uint64_t>& surfaceEdges,
                          const std::vector<char>& removed, bool loopOrder, std::vector<Vec3>& apex, HoleRepair& how) {
    const SurfaceMesh& s = c.surface;
    std::vector<Vec3> points;
    BBox box;
    for (const std::int32_t v : loop.vertices) {
        points.push_back(s.vertices[std::size_t(v)]);
        box.extend(points.back());
    }
    const Vec3 centre = loopCentroid(points), normal = newellNormal(points).normalized();
    const double radius = 0.5 * loopDiameterMm(points);
    for (const double f : {1.0, -1.0}) box.extend(centre + f * radius * normal);  // the raised fans' apexes
    const std::vector<std::int32_t> near = trianglesMeeting(s, box, [&](std::size_t t) { return removed[t] != 0; });
    const auto global = [&](std::vector<Tri> local) {
        for (Tri& t : local)
            for (auto& v : t) v = v < std::int32_t(loop.vertices.size()) ? loop.vertices[std::size_t(v)] : std::int32_t(s.vertices.size());
        return local;
    };
    const auto allowed = [&](int i, int j) {
        return !surfaceEdges.count(edgeKey(loop.vertices[std::size_t(i)], loop.vertices[std::size_t(j)]));
    };
    const std::array<Label, 2> sides = loopOrder ? std::array<Label, 2>{loop.pair[1], loop.pair[0]} : loop.pair;
    const auto wedgeDeg = [&](const Candidate& k) {
        std::vector<Tri> laid = k.triangles;
        if (!loopOrder)
            for (Tri& t : laid) std::swap(t[1], t[2]);
        return patchSmallestWedgeDeg(c, near, laid, k.apex, sides);
    };
    const std::vector<Candidate> flat = {{global(earClipLoop(points, allowed)), {}, HoleRepair::EarClipping},
                                         {global(minimumAreaLoop(points, allowed)), {}, HoleRepair::MinimumArea},
                                         {global(centroidFan(points.size())), {centre}, HoleRepair::CentroidFan}};
    std::vector<Candidate> clean;
    for (const Candidate& k : flat)
        if (!k.triangles.empty() && patchIsClean(s, k.triangles, k.apex, near)) clean.push_back(k);
    apex.clear();
    if (clean.empty()) return {};
    const double firstDeg = wedgeDeg(clean.front());
    if (firstDeg < kHoleMinWedgeDeg)
        for (const double f : {0.125, -0.125, 0.25, -0.25, 0.375, -0.375, 0.5, -0.5, 0.75, -0.75, 1.0, -1.0}) {
            Candidate raised{global(centroidFan(points.size())), {centre + f * radius * normal}, HoleRepair::RaisedFan};
            if (patchIsClean(s, raised.triangles, raised.apex, near)) clean.push_back(std::move(raised));
        }
    const Candidate& chosen = clean[widestWedge(c, loop, near, clean, firstDeg, wedgeDeg)];
    apex = chosen.apex;
    how = chosen.how;
    return chosen.triangles;
}

}  // namespace

std::size_t HoleFillStats::trianglesAdded() const {
    std::size_t n = 0;
    for (const FilledHole& h : filled) n += h.how == HoleRepair::LidRemoved ? 0 : h.triangles;
    return n;
}

std::size_t HoleFillStats::trianglesRemoved() const {
    std::size_t n = 0;
    for (const FilledHole& h : filled) n += h.how == HoleRepair::LidRemoved ? h.triangles : 0;
    return n;
}

std::size_t HoleFillStats::verticesAdded() const {
    return std::size_t(std::count_if(filled.begin(), filled.end(), [](const FilledHole& h) { return h.how == HoleRepair::CentroidFan || h.how == HoleRepair::RaisedFan; }));
}

const char* holeRepairName(HoleRepair r) {
    switch (r) {
    case HoleRepair::EarClipping: return "ear clipping";
    case HoleRepair::MinimumArea: return "minimum area";
    case HoleRepair::CentroidFan: return "centroid fan";
    case HoleRepair::RaisedFan: return "raised fan";
    case HoleRepair::TetCut: return "cut from tets";
    case HoleRepair::LidRemoved: return "lid removed";
    }
    return "?";
}

double HoleFillStats::largestHoleMm() const {
    double d = 0;
    for (const FilledHole& h : filled) d = std::max(d, h.diameterMm);
    return d;
}

HoleFillStats fillSurfaceHoles(InterfaceComplex& complex) {
    HoleFillStats stats;
    const HoleLoops found = holeLoops(complex);
    stats.strayEdges = found.strayEdges;
    if (found.loops.empty()) return stats;
    SurfaceMesh& s = complex.surface;
    std::unordered_set<std::uint64_t> surfaceEdges, closed;
    for (const Tri& t : s.triangles)
        for (int k = 0; k < 3; ++k) surfaceEdges.insert(edgeKey(t[std::size_t(k)], t[std::size_t((k + 1) % 3)]));
    std::map<std::array<Label, 2>, std::unordered_set<std::uint64_t>> openEdges;  // per sheet
    for (const HoleLoop& loop : found.loops)
        for (std::size_t i = 0; i < loop.vertices.size(); ++i)
            openEdges[loop.pair].insert(edgeKey(loop.vertices[i], loop.vertices[(i + 1) % loop.vertices.size()]));
    const VertexTriangles vt = vertexTriangles(s.triangles, s.vertices.size());  // the input's triangles
    std::vector<char> removed(s.triangles.size(), 0);
    for (const HoleLoop& loop : found.loops) {
        const std::size_t n = loop.vertices.size();
        std::unordered_set<std::uint64_t> loopEdges;
        std::vector<Vec3> points;
        for (std::size_t i = 0; i < n; ++i) {
            loopEdges.insert(edgeKey(loop.vertices[i], loop.vertices[(i + 1) % n]));
            points.push_back(s.vertices[std::size_t(loop.vertices[i])]);
        }
        // a lid taken out for another loop has closed this one too
        if (std::any_of(loopEdges.begin(), loopEdges.end(), [&](std::uint64_t e) { return closed.count(e) > 0; })) continue;
        FilledHole hole{loop.pair, n, loopDiameterMm(points), loopCentroid(points), HoleRepair::LidRemoved, 0};
        const std::vector<std::int32_t> lid = lidInsideLoop(complex, vt, loop, openEdges[loop.pair], removed);
        if (!lid.empty()) {
            for (const std::int32_t t : lid) {
                removed[std::size_t(t)] = 1;
                const Tri& tri = s.triangles[std::size_t(t)];
                for (int k = 0; k < 3; ++k) closed.insert(edgeKey(tri[std::size_t(k)], tri[std::size_t((k + 1) % 3)]));
            }
            hole.triangles = lid.size();
            stats.filled.push_back(hole);
            continue;
        }
        // The patch is wound with its normal into pair[1]; turned over when the sheet says so.
        const bool loopOrder = sheetUsesLoopOrder(complex, loop, loopEdges);
        std::vector<Vec3> apex;
        std::vector<Tri> patch = patchFor(complex, loop, surfaceEdges, removed, loopOrder, apex, hole.how);
        if (patch.empty()) {
            stats.left.push_back(hole);
            continue;
        }
        for (Tri t : patch) {
            if (!loopOrder) std::swap(t[1], t[2]);
            s.triangles.push_back(t);
            removed.push_back(0);
            complex.sides.push_back(loopOrder ? std::array<Label, 2>{loop.pair[1], loop.pair[0]} : loop.pair);
            for (int k = 0; k < 3; ++k) surfaceEdges.insert(edgeKey(t[std::size_t(k)], t[std::size_t((k + 1) % 3)]));
        }
        s.vertices.insert(s.vertices.end(), apex.begin(), apex.end());
        hole.triangles = patch.size();
        stats.filled.push_back(hole);
    }
    if (stats.trianglesRemoved() > 0) dropTriangles(complex, removed);
    return stats;
}

nlohmann::json toJson(const HoleFillStats& stats) {
    nlohmann::json holes = nlohmann::json::array();
    for (const FilledHole& h : stats.filled)
        holes.push_back({{"between", {labelName(h.pair[0]), labelName(h.pair[1])}},
                         {"boundary_edges", h.boundaryEdges},
                         {"diameter_mm", h.diameterMm},
                         {"centre_mm", {h.centre.x(), h.centre.y(), h.centre.z()}},
                         {"triangles", h.triangles},
                         {"repair", holeRepairName(h.how)}});
    return {{"holes_filled", stats.filled.size()},
            {"triangles_added", stats.trianglesAdded()},
            {"vertices_added", stats.verticesAdded()},
            {"triangles_removed", stats.trianglesRemoved()},
            {"largest_hole_mm", stats.largestHoleMm()},
            {"wedge_flips", stats.wedgeFlips},
            {"wedge_bumps", stats.wedgeBumps},
            {"smallest_patch_wedge_deg", {{"before", stats.smallestPatchWedgeBeforeDeg}, {"after", stats.smallestPatchWedgeAfterDeg}}},
            {"holes", holes}};
}

}  // namespace jawmesh
