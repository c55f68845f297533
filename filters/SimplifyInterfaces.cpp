// The simplification of SimplifyInterfaces.h: the block partition and its passes (each block
// simplified by BlockSimplifier.h), and simplifyInterfaces with its checks and statistics.
#include "filters/SimplifyInterfaces.h"

#include "filters/BlockSimplifier.h"
#include "filters/NearTeeth.h"
#include "filters/PlateThickness.h"
#include "filters/RegionWedges.h"
#include "io/Angles.h"
#include "io/ResourceUsage.h"

#include "filters/SelfIntersections.h"
#include "filters/SimplifyState.h"
#include "filters/SplitCorners.h"
#include "filters/ShellSeeds.h"
#include "filters/TriangleGeometry.h"
#include "io/Error.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <unordered_map>

namespace jawmesh {

nlohmann::json toJson(const SimplifyStats& s) {
    return {{"input_triangles", s.inputTriangles},
            {"output_triangles", s.outputTriangles},
            {"output_vertices", s.outputVertices},
            {"collapses", s.collapses},
            {"triangles_per_kind", s.trianglesPerKind},
            {"max_error_mm", s.maxErrorMm},
            {"max_error_near_teeth_mm", s.maxErrorNearTeethMm},
            {"min_angle_deg", s.minAngleDeg},
            {"min_angle_histogram",
             {{"bins_deg", {0, 5, 10, 15, 20, 30, 40, 60}}, {"triangles", s.minAngleHistogram}}},
            {"seconds", s.seconds},
            {"exhaustive_rerun", s.exhaustiveRerun},
            {"corner_splits", s.cornerSplits},
            {"min_wedge_deg", s.minWedgeDeg},
            {"edges_below_min_wedge", s.edgesBelowMinWedge},
            {"plate_vertices", s.plateVertices}};
}

nlohmann::json toJson(const SimplifyOptions& o) {
    return {{"tooth_error_mm", o.toothErrorMm},       {"pdl_error_mm", o.pdlErrorMm},
            {"bone_error_mm", o.boneErrorMm},         {"bone_far_error_mm", o.boneFarErrorMm},
            {"bone_near_teeth_mm", o.boneNearTeethMm}, {"pdl_max_edge_mm", o.pdlMaxEdgeMm},
            {"cap_max_edge_mm", o.capMaxEdgeMm},      {"tooth_max_edge_mm", o.toothMaxEdgeMm},
            {"bone_max_edge_mm", o.boneMaxEdgeMm},    {"min_angle_deg", o.minAngleDeg},
            {"min_wedge_deg", o.minWedgeDeg},         {"plate_max_mm", o.plateMaxMm},
            {"plate_error_fraction", o.plateErrorFraction}, {"plate_edge_factor", o.plateEdgeFactor}};
}

InterfaceBounds boundsOf(const SimplifyOptions& o) {
    return InterfaceBounds{o.toothErrorMm,  o.pdlErrorMm,   o.boneErrorMm,    o.boneFarErrorMm,
                           o.pdlMaxEdgeMm, o.capMaxEdgeMm, o.toothMaxEdgeMm, o.boneMaxEdgeMm};
}

AdaptiveOptions matchedTo(const SimplifyOptions& options, AdaptiveOptions adaptive) {
    adaptive.bounds = boundsOf(options);
    adaptive.boneNearTeethMm = options.boneNearTeethMm;
    adaptive.minWedgeDeg = options.minWedgeDeg;
    return adaptive;
}

std::string interfaceKind(Label a, Label b) {
    using K = LabelKind;
    const auto kind = [](Label l) { return l == kOutsideLabel ? K::Outside : labelKind(l); };
    K ka = kind(a), kb = kind(b);
    if (ka > kb) std::swap(ka, kb);  // enum order: Outside, Bone, Tooth, Pdl
    if (ka == K::Tooth && kb == K::Pdl) return "tooth/pdl";
    if (ka == K::Bone && kb == K::Pdl) return "pdl/bone";
    if (ka == K::Outside && kb == K::Tooth) return "tooth/outside";
    if (ka == K::Outside && kb == K::Pdl) return "pdl/outside";
    if (ka == K::Outside && kb == K::Bone) return "bone/outside";
    return "other";
}

namespace {

using simplify::Block;
using simplify::BlockResult;
using simplify::InputSurface;
using simplify::State;

/// Splits the live triangles into cubic blocks (by centroid, grid shifted by offsetMm), marks the
/// vertices shared by two blocks as border, and gives every block the nearby triangles of its
/// neighbours as obstacles. blockMm <= 0: one block with everything, no border.
std::vector<Block> makeBlocks(const State& st, double blockMm, double offsetMm, double marginMm,
                              std::vector<char>& border) {
    const std::size_t nt = st.tris.size();
    border.assign(st.points->size(), 0);
    if (blockMm <= 0) {
        Block all;
        all.tris.resize(nt);
        for (std::size_t t = 0; t < nt; ++t) all.tris[t] = std::int32_t(t);
        return {all};
    }
    const auto& P = *st.points;
    using Cell = std::array<int, 3>;
    std::vector<Cell> cellOf(nt);
    std::map<Cell, std::size_t> index;
    for (std::size_t t = 0; t < nt; ++t) {
        const Tri& f = st.tris[t];
        const Vec3 c = (P[std::size_t(f[0])] + P[std::size_t(f[1])] + P[std::size_t(f[2])]) / 3.0;
        for (int k = 0; k < 3; ++k) cellOf[t][std::size_t(k)] = int(std::floor((c[k] - offsetMm) / blockMm));
        index.emplace(cellOf[t], 0);
    }
    std::size_t n = 0;
    for (auto& [cell, i] : index) i = n++;  // blocks in cell order: deterministic
    std::vector<Block> blocks(n);
    std::vector<std::int32_t> owner(P.size(), -1);
    for (std::size_t t = 0; t < nt; ++t) {
        const std::size_t b = index.at(cellOf[t]);
        blocks[b].tris.push_back(std::int32_t(t));
        for (std::int32_t v : st.tris[t]) {
            if (owner[std::size_t(v)] < 0) owner[std::size_t(v)] = std::int32_t(b);
            else if (owner[std::size_t(v)] != std::int32_t(b)) border[std::size_t(v)] = 1;
        }
    }
    // Obstacles: a neighbour's triangle whose box comes within marginMm of the block's cell.
    for (std::size_t t = 0; t < nt; ++t) {
        const Tri& f = st.tris[t];
        BBox box;
        for (std::int32_t v : f) box.extend(P[std::size_t(v)]);
        const Cell& c = cellOf[t];
        // Per axis, which neighbours (-1, +1) the box comes near; most triangles sit inside their
        // cell and skip the 26 lookups (the test below then decides exactly, as before).
        bool reach[3][2];
        for (int k = 0; k < 3; ++k) {
            reach[k][0] = box.min[k] <= c[std::size_t(k)] * blockMm + offsetMm + marginMm;
            reach[k][1] = box.max[k] >= (c[std::size_t(k)] + 1) * blockMm + offsetMm - marginMm;
        }
        if (!(reach[0][0] || reach[0][1] || reach[1][0] || reach[1][1] || reach[2][0] || reach[2][1])) continue;
        const auto skip = [&](int k, int d) { return d != 0 && !reach[k][d > 0 ? 1 : 0]; };
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    if (!dx && !dy && !dz) continue;
                    if (skip(0, dx) || skip(1, dy) || skip(2, dz)) continue;
                    const Cell nb{c[0] + dx, c[1] + dy, c[2] + dz};
                    const auto it = index.find(nb);
                    if (it == index.end()) continue;
                    bool near = true;
                    for (int k = 0; k < 3 && near; ++k) {
                        const double lo = nb[std::size_t(k)] * blockMm + offsetMm - marginMm;
                        const double hi = (nb[std::size_t(k)] + 1) * blockMm + offsetMm + marginMm;
                        near = box.max[k] >= lo && box.min[k] <= hi;
                    }
                    if (near) blocks[it->second].obstacles.push_back(std::int32_t(t));
                }
    }
    return blocks;
}

/// One pass: every block simplified in parallel (blocks only write their own data), then the
/// results put back in block order.
std::size_t runPass(State& st, double blockMm, double offsetMm, const SimplifyOptions& o, Progress& progress,
                    ProgressStage& stage, double from, double to) {
    std::vector<char> border;
    const double margin = 2.0 * std::max({o.boneMaxEdgeMm, o.toothMaxEdgeMm, o.pdlMaxEdgeMm});
    const std::vector<Block> blocks = makeBlocks(st, blockMm, offsetMm, margin, border);
    std::vector<BlockResult> results(blocks.size());
    std::atomic<std::size_t> done{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 1), [&](const auto& r) {
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
            progress.checkCancelled();
            simplify::BlockSimplifier s(st, blocks[b], border, o);
            s.run(progress);
            results[b] = s.result();
            const std::size_t d = ++done;
            if (tbb::this_task_arena::current_thread_index() == 0)
                stage.update(from + (to - from) * double(d) / double(blocks.size()));
        }
    });
    State next;
    std::size_t collapses = 0;
    for (BlockResult& r : results) {
        next.tris.insert(next.tris.end(), r.tris.begin(), r.tris.end());
        next.sides.insert(next.sides.end(), r.sides.begin(), r.sides.end());
        for (auto& p : r.pts) next.pts.push_back(std::move(p));
        for (std::uint64_t key : r.takenCurves) st.curvePts.erase(key);
        for (auto& [key, pts] : r.curves) st.curvePts[key] = std::move(pts);
        collapses += r.collapses;
    }
    st.tris = std::move(next.tris);
    st.sides = std::move(next.sides);
    st.pts = std::move(next.pts);
    return collapses;
}

/// The state's live triangles as a compact complex (seeds not set).
InterfaceComplex complexOf(const State& st, const std::vector<Vec3>& points) {
    InterfaceComplex out;
    std::vector<std::int32_t> remap(points.size(), -1);
    for (std::size_t t = 0; t < st.tris.size(); ++t) {
        Tri f = st.tris[t];
        for (auto& v : f) {
            if (remap[std::size_t(v)] < 0) {
                remap[std::size_t(v)] = std::int32_t(out.surface.vertices.size());
                out.surface.vertices.push_back(points[std::size_t(v)]);
            }
            v = remap[std::size_t(v)];
        }
        out.surface.triangles.push_back(f);
        out.sides.push_back(st.sides[t]);
    }
    return out;
}

}  // namespace

InterfaceComplex simplifyInterfaces(const InterfaceComplex& input, const SimplifyOptions& options,
                                    Progress& progress, SimplifyStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    if (input.sides.size() != input.surface.triangles.size())
        throw Error("simplification: one label pair per triangle is required");
    if (!input.carried.empty() && input.carried.size() != input.surface.triangles.size())
        throw Error("simplification: carried vertices must be given per triangle");
    if (input.sampleErrorMm.size() > input.surface.vertices.size())
        throw Error("simplification: more sample errors than vertices");
    for (double x : {options.toothErrorMm, options.pdlErrorMm, options.boneErrorMm, options.boneFarErrorMm, options.boneNearTeethMm,
                     options.pdlMaxEdgeMm, options.capMaxEdgeMm, options.toothMaxEdgeMm, options.boneMaxEdgeMm,
                     options.plateMaxMm, options.plateErrorFraction, options.plateEdgeFactor})
        if (!(x >= 0) || !std::isfinite(x)) throw Error("simplification: error bounds and edge lengths must be >= 0");
    if (!(options.minAngleDeg >= 0 && options.minAngleDeg < 60))
        throw Error("simplification: minimum angle must be in [0, 60) degrees");
    if (!(options.maxNormalTurnDeg > 0 && options.maxNormalTurnDeg <= 180))
        throw Error("simplification: maximum normal turn must be in (0, 180] degrees");
    if (!(options.minWedgeDeg >= 0 && options.minWedgeDeg < 90))
        throw Error("simplification: minimum region wedge must be in [0, 90) degrees");
    if (!(options.blockMm >= 0)) throw Error("simplification: block size must be >= 0");
    const std::size_t nv = input.surface.vertices.size();
    std::size_t corners = 0;  // vertices past the corners are carried ones (quadrics only for corners)
    for (const Tri& f : input.surface.triangles)
        for (std::int32_t v : f) {
            if (v < 0 || std::size_t(v) >= nv) throw Error("simplification: triangle index out of range");
            corners = std::max(corners, std::size_t(v) + 1);
        }
    for (const auto& carried : input.carried)
        for (std::int32_t v : carried)
            if (v < std::int32_t(corners) || std::size_t(v) >= nv)
                throw Error("simplification: a carried vertex must follow every corner");
    ProgressStage stage(progress, "simplify interfaces");

    // The starting state is rebuilt rather than kept for a possible rerun: a copy would hold
    // ~100 bytes per input vertex for the whole run (about 1.3 GB on a mandible).
    const auto& P = input.surface.vertices;
    std::vector<char> nearTeeth = verticesNearTeeth(input, options.boneNearTeethMm);
    // Thin plates are measured near the teeth only (the crest, pinched PDL): far away the bone is
    // millimetres thick, and the rays would cost seconds for nothing.
    const std::vector<float> plateMm =
        options.plateMaxMm > 0 ? plateThicknessMm(input, nearTeeth, PlateOptions{options.plateMaxMm})
                               : std::vector<float>(nv, std::numeric_limits<float>::infinity());
    const InputSurface inputSurface(input);
    const auto startState = [&] {
        State st;
        st.points = &P;
        st.input = &inputSurface;
        st.tris = input.surface.triangles;
        st.sides = input.sides;
        st.pts.resize(st.tris.size());
        st.quadrics.resize(corners);
        st.err.assign(nv, 0.0f);
        // The adaptive extraction's carried vertices start on their triangles, at their distance.
        for (std::size_t t = 0; t < input.carried.size(); ++t) {
            st.pts[t] = input.carried[t];
            const Tri& f = st.tris[t];
            for (std::int32_t p : st.pts[t])
                st.err[std::size_t(p)] = float(std::sqrt(squaredDistanceToTriangle(P[std::size_t(p)], P[std::size_t(f[0])],
                                                                                   P[std::size_t(f[1])], P[std::size_t(f[2])])));
        }
        st.nearTeeth = nearTeeth;
        st.plateMm = &plateMm;
        st.spentMm = &input.sampleErrorMm;
        for (const Tri& f : st.tris) {
            const Vec3 n2 = (P[std::size_t(f[1])] - P[std::size_t(f[0])]).cross(P[std::size_t(f[2])] - P[std::size_t(f[0])]);
            const double len = n2.norm();
            if (len == 0) continue;
            const Vec3 n = n2 / len;
            for (std::int32_t v : f) st.quadrics[std::size_t(v)].addPlane(n, -n.dot(P[std::size_t(f[0])]), 0.5 * len);
        }
        return st;
    };
    State st = startState();
    // Blocks, blocks shifted by half a block (the first pass's borders inside), then everything.
    std::size_t collapses = 0;
    const auto simplify = [&](const SimplifyOptions& o) {
        if (o.blockMm > 0) {
            collapses += runPass(st, o.blockMm, 0.0, o, progress, stage, 0.0, 0.6);
            collapses += runPass(st, o.blockMm, 0.5 * o.blockMm, o, progress, stage, 0.6, 0.9);
        }
        collapses += runPass(st, 0.0, 0.0, o, progress, stage, 0.9, 0.97);
    };
    simplify(options);
    InterfaceComplex out = complexOf(st, P);
    SelfIntersectionReport check = findSelfIntersections(out.surface);
    bool rerun = false;
    if (!check.pairs.empty() && !options.exhaustiveIntersectionChecks) {
        // The local test missed two sheets meeting away from the collapse: start again with the
        // exhaustive test (slower, but every collapse is then checked against everything).
        st = startState();
        collapses = 0;
        SimplifyOptions exhaustive = options;
        exhaustive.exhaustiveIntersectionChecks = true;
        simplify(exhaustive);
        out = complexOf(st, P);
        check = findSelfIntersections(out.surface);
        rerun = true;
    }
    if (!check.pairs.empty())
        throw Error("simplification: the output has " + std::to_string(check.pairs.size()) +
                    " intersecting triangle pairs (the input surface must be intersection-free)");
    const std::size_t cornerSplits = splitThreeTriangleCorners(out);  // forced slivers (SplitCorners.h)
    out.seeds = seedsInsideShells(out);  // grid seeds may have left a thin region (ShellSeeds.h)
    SimplifyStats local;
    SimplifyStats& s = stats ? *stats : local;
    s = SimplifyStats{};
    s.exhaustiveRerun = rerun;
    s.cornerSplits = cornerSplits;
    s.plateVertices = std::size_t(std::count_if(plateMm.begin(), plateMm.end(), [](float x) { return std::isfinite(x); }));

    s.inputTriangles = input.surface.triangles.size();
    s.outputTriangles = out.surface.triangles.size();
    s.outputVertices = out.surface.vertices.size();
    s.collapses = collapses;
    s.maxErrorMm = st.err.empty() ? 0.0 : double(*std::max_element(st.err.begin(), st.err.end()));
    for (std::size_t v = 0; v < st.err.size(); ++v)
        if (nearTeeth[v]) s.maxErrorNearTeethMm = std::max(s.maxErrorNearTeethMm, double(st.err[v]));
    s.minAngleDeg = 180;
    const double bins[] = {5, 10, 15, 20, 30, 40};
    for (std::size_t t = 0; t < out.surface.triangles.size(); ++t) {
        const Tri& f = out.surface.triangles[t];
        const double a = minAngleDeg(out.surface.vertices[f[0]], out.surface.vertices[f[1]], out.surface.vertices[f[2]]);
        s.minAngleDeg = std::min(s.minAngleDeg, a);
        s.minAngleHistogram[std::size_t(std::upper_bound(std::begin(bins), std::end(bins), a) - std::begin(bins))]++;
        s.trianglesPerKind[interfaceKind(out.sides[t][0], out.sides[t][1])]++;
    }
    const RegionWedgeStats wedges = measureRegionWedges(out, options.minWedgeDeg);
    s.minWedgeDeg = wedges.smallestDeg;
    s.edgesBelowMinWedge = wedges.edgesBelow;
    s.seconds = secondsSince(start);
    return out;
}

}  // namespace jawmesh
