// Hole repair before TetGen: passes of local triangulations, then a patch of tet faces in two ways
// (kHoleCutWays), each taken only when it stays in the balls around the holes.
#include "tet/RepairHoles.h"

#include "filters/FillSurfaceHoles.h"
#include "filters/OpenRegionEdges.h"
#include "filters/PatchWedgeOpening.h"
#include "io/Error.h"
#include "tet/HoleCut.h"
#include "tet/HolePoints.h"
#include "tet/TetgenAdapter.h"

#include <limits>
#include <map>
#include <optional>
#include <set>

namespace jawmesh {
namespace {

/// One way of cutting: TetGen's switches for the quick run and whether the floods stay in the balls.
struct HoleCutWay {
    const char* switches;
    bool inBalls;
    bool sourcesAtTheirDistance;  // tet/HoleCut.h
};
/// First in the balls over the convex hull's tets (quality-bounded, so no tet spans far through a
/// hole); then, where that left a hole of its own (a rim tet that two triangles give different
/// sides), over all tets of the carved mesh (TetGen drops what it reaches from the hull).
constexpr HoleCutWay kHoleCutWays[] = {{"pczQYMq2", true, true}, {"pzQYM", false, false}};

/// Per patch triangle, the nearest hole whose ball holds its centroid; nothing when one lies in
/// no ball (the patch is not local).
std::optional<std::vector<std::size_t>> holeOfEachTriangle(const HoleCutPatch& patch, const TetMesh& mesh,
                                                           const std::vector<FilledHole>& holes) {
    std::vector<std::size_t> holeOf;
    for (const Tri& t : patch.triangles) {
        const auto& n = mesh.nodes;
        const Vec3 p = (n[std::size_t(t[0])] + n[std::size_t(t[1])] + n[std::size_t(t[2])]) / 3.0;
        std::size_t nearest = holes.size();
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t h = 0; h < holes.size(); ++h) {
            const double d = (p - holes[h].centre).norm();
            if (d <= kHoleBallPerDiameter * holes[h].diameterMm && d < best) {
                best = d;
                nearest = h;
            }
        }
        if (nearest == holes.size()) return std::nullopt;
        holeOf.push_back(nearest);
    }
    return holeOf;
}

/// Adds the patch's triangles to `c`, and the nodes TetGen added that they use.
void addPatch(InterfaceComplex& c, const HoleCutPatch& patch, const TetMesh& mesh) {
    // TetGen keeps the input points first, in order (-z); its own points are appended.
    const std::size_t inputPoints = c.surface.vertices.size();
    std::map<std::int32_t, std::int32_t> added;
    for (std::size_t i = 0; i < patch.triangles.size(); ++i) {
        Tri t = patch.triangles[i];
        for (auto& v : t) {
            if (std::size_t(v) < inputPoints) continue;
            const auto [it, fresh] = added.emplace(v, std::int32_t(c.surface.vertices.size()));
            if (fresh) c.surface.vertices.push_back(mesh.nodes[std::size_t(v)]);
            v = it->second;
        }
        c.surface.triangles.push_back(t);
        c.sides.push_back(patch.sides[i]);
    }
}

/// The holes no local triangulation closed (stats.left) are patched with tet faces: a quick
/// tetrahedralization of the open complex with points through the holes (tet/HolePoints.h; no
/// quality bound, in a child process, the convex hull kept so the holes have tets to cut),
/// labeled as tet/HoleCut.h says in a ball around each hole (around its loop's centroid). The
/// patch is taken only when each of its faces lies in such a ball: a repair is local or it is not
/// made (then c and stats stay as they are).
void patchHolesFromTets(InterfaceComplex& c, const std::vector<double>& seedVolumeBoundsMm3, const HoleCutWay& way,
                        HoleFillStats& stats, std::uint64_t& childPeakBytes) {
    const TetgenRun run{way.switches, kTetgenDefaultOptMaxDihedralDeg, seedVolumeBoundsMm3};
    InterfaceComplex withPoints = c;  // the points are TetGen's input points after c's vertices
    const std::vector<Vec3> points = pointsInHoles(c.surface, stats.left);
    withPoints.surface.vertices.insert(withPoints.surface.vertices.end(), points.begin(), points.end());
    const TetgenMesh raw = runTetgenInChild(withPoints, run, childPeakBytes);
    std::vector<HoleBall> balls;
    for (const FilledHole& h : stats.left)
        balls.push_back({h.centre, way.inBalls ? kHoleBallPerDiameter * h.diameterMm : std::numeric_limits<double>::infinity()});
    const HoleCutPatch patch = holeCutPatch(c, raw.mesh, raw.facets, balls, way.sourcesAtTheirDistance);
    if (!patch.local) return;
    const std::optional<std::vector<std::size_t>> holeOf = holeOfEachTriangle(patch, raw.mesh, stats.left);
    if (!holeOf) return;  // not local: leave the complex as it is
    addPatch(c, patch, raw.mesh);
    std::vector<std::size_t> count(stats.left.size(), 0);
    for (std::size_t h : *holeOf) ++count[h];
    for (std::size_t h = 0; h < stats.left.size(); ++h) {
        if (count[h] == 0) continue;
        FilledHole hole = stats.left[h];
        hole.how = HoleRepair::TetCut;
        hole.triangles = count[h];
        stats.filled.push_back(hole);
    }
    stats.left.clear();
}

/// Local triangulations, pass after pass while a pass closes something (at most kHoleRepairPasses).
void fillPasses(InterfaceComplex& repaired, HoleFillStats& stats) {
    for (int pass = 0; pass < kHoleRepairPasses; ++pass) {
        const HoleFillStats more = fillSurfaceHoles(repaired);
        stats.filled.insert(stats.filled.end(), more.filled.begin(), more.filled.end());
        stats.left = more.left;
        stats.strayEdges = more.strayEdges;
        if (more.filled.empty() || (more.left.empty() && more.strayEdges == 0)) break;
    }
}

/// The repair's triangles (those of `repaired` that `input` does not have, by their corners: the
/// fill passes renumber vertices) are flipped or bumped where they fold against a neighbour at a
/// region wedge under kHoleMinWedgeDeg (filters/PatchWedgeOpening.h).
void openSharpPatchWedges(const InterfaceComplex& input, InterfaceComplex& repaired, HoleFillStats& stats) {
    using Corners = std::array<std::array<double, 3>, 3>;
    const auto corners = [](const InterfaceComplex& c, const Tri& t) {
        Corners k;
        for (std::size_t i = 0; i < 3; ++i) {
            const Vec3& v = c.surface.vertices[std::size_t(t[i])];
            k[i] = {v.x(), v.y(), v.z()};
        }
        std::sort(k.begin(), k.end());
        return k;
    };
    std::set<Corners> given;
    for (const Tri& t : input.surface.triangles) given.insert(corners(input, t));
    std::vector<char> added(repaired.surface.triangles.size(), 0);
    for (std::size_t t = 0; t < added.size(); ++t) added[t] = given.count(corners(repaired, repaired.surface.triangles[t])) ? 0 : 1;
    const PatchWedgeStats opened = openPatchWedges(repaired, added, kHoleMinWedgeDeg);
    stats.wedgeFlips = opened.flips;
    stats.wedgeBumps = opened.bumps;
    stats.smallestPatchWedgeBeforeDeg = opened.smallestWedgeBeforeDeg;
    stats.smallestPatchWedgeAfterDeg = opened.smallestWedgeAfterDeg;
}

}  // namespace

const InterfaceComplex& repairHoles(const InterfaceComplex& input, InterfaceComplex& repaired,
                                    const std::vector<double>& seedVolumeBoundsMm3, TetStats& st) {
    if (openRegionEdges(input).empty()) return input;
    repaired = input;
    HoleFillStats& stats = st.holeRepair;
    fillPasses(repaired, stats);
    if (stats.left.empty() || stats.strayEdges > 0) {
        openSharpPatchWedges(input, repaired, stats);
        return repaired;
    }
    const InterfaceComplex filled = repaired;
    const HoleFillStats filledStats = stats;
    for (const HoleCutWay& way : kHoleCutWays) {
        repaired = filled;
        stats = filledStats;
        try {
            patchHolesFromTets(repaired, seedVolumeBoundsMm3, way, stats, st.childPeakMemoryBytes);
        } catch (const Error& e) {
            st.failedAttempts.push_back(std::string("hole patch from tets (") + way.switches + "): " + e.what());
            continue;
        }
        if (!stats.left.empty()) continue;  // not local
        if (!openRegionEdges(repaired).empty()) fillPasses(repaired, stats);
        if (openRegionEdges(repaired).empty()) break;
    }
    openSharpPatchWedges(input, repaired, stats);
    return repaired;
}

}  // namespace jawmesh
