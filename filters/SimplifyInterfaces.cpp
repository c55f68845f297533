// The simplification of SimplifyInterfaces.h: argument checks, the starting state (quadrics,
// carried vertices, thin plates), the passes (SimplifyPasses.h) with an exhaustive rerun when the
// output check finds an intersection, and the output's statistics.
#include "filters/SimplifyInterfaces.h"

#include "filters/NearTeeth.h"
#include "filters/PlateThickness.h"
#include "filters/RegionWedges.h"
#include "filters/SelfIntersections.h"
#include "filters/ShellSeeds.h"
#include "filters/SimplifyPasses.h"
#include "filters/SimplifyState.h"
#include "filters/SplitCorners.h"
#include "filters/TriangleGeometry.h"
#include "io/Error.h"
#include "io/ResourceUsage.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

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

using simplify::InputSurface;
using simplify::State;

/// Throws Error unless every option is in its range.
void checkOptions(const SimplifyOptions& options) {
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
}

/// Throws Error unless the input's per-triangle and per-vertex arrays have their sizes.
void checkInputArrays(const InterfaceComplex& input) {
    if (input.sides.size() != input.surface.triangles.size())
        throw Error("simplification: one label pair per triangle is required");
    if (!input.carried.empty() && input.carried.size() != input.surface.triangles.size())
        throw Error("simplification: carried vertices must be given per triangle");
    if (input.sampleErrorMm.size() > input.surface.vertices.size())
        throw Error("simplification: more sample errors than vertices");
}

/// Throws Error unless the input's indices are in range; returns the number of corners (vertices
/// past them are carried ones, which get no quadric).
std::size_t checkedCorners(const InterfaceComplex& input) {
    const std::size_t nv = input.surface.vertices.size();
    std::size_t corners = 0;
    for (const Tri& f : input.surface.triangles)
        for (std::int32_t v : f) {
            if (v < 0 || std::size_t(v) >= nv) throw Error("simplification: triangle index out of range");
            corners = std::max(corners, std::size_t(v) + 1);
        }
    for (const auto& carried : input.carried)
        for (std::int32_t v : carried)
            if (v < std::int32_t(corners) || std::size_t(v) >= nv)
                throw Error("simplification: a carried vertex must follow every corner");
    return corners;
}

/// What the starting state refers to, measured once on the input.
struct InputMeasures {
    std::vector<char> nearTeeth;  ///< per input vertex (NearTeeth.h)
    std::vector<float> plateMm;   ///< per input vertex: the thin plate it bounds, infinite off plates
    InputSurface surface;
};

InputMeasures measureInput(const InterfaceComplex& input, const SimplifyOptions& options) {
    std::vector<char> nearTeeth = verticesNearTeeth(input, options.boneNearTeethMm);
    // Thin plates are measured near the teeth only (the crest, pinched PDL): far away the bone is
    // millimetres thick, and the rays would cost seconds for nothing.
    std::vector<float> plateMm =
        options.plateMaxMm > 0 ? plateThicknessMm(input, nearTeeth, PlateOptions{options.plateMaxMm})
                               : std::vector<float>(input.surface.vertices.size(), std::numeric_limits<float>::infinity());
    return {std::move(nearTeeth), std::move(plateMm), InputSurface(input)};
}

/// The adaptive extraction's carried vertices start on their triangles, at their distance (each
/// carried by one triangle, so the triangles are placed in parallel).
void placeCarriedVertices(const InterfaceComplex& input, State& st) {
    const auto& P = input.surface.vertices;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, input.carried.size(), 4096), [&](const auto& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            st.pts[t] = input.carried[t];
            const Tri& f = st.tris[t];
            for (std::int32_t p : st.pts[t])
                st.err[std::size_t(p)] = float(std::sqrt(squaredDistanceToTriangle(
                    P[std::size_t(p)], P[std::size_t(f[0])], P[std::size_t(f[1])], P[std::size_t(f[2])])));
        }
    });
}

/// Every corner's quadric: the planes of its triangles, weighted by their areas.
void addTriangleQuadrics(State& st) {
    const auto& P = *st.points;
    for (const Tri& f : st.tris) {
        const Vec3 n2 = (P[std::size_t(f[1])] - P[std::size_t(f[0])]).cross(P[std::size_t(f[2])] - P[std::size_t(f[0])]);
        const double len = n2.norm();
        if (len == 0) continue;
        const Vec3 n = n2 / len;
        for (std::int32_t v : f) st.quadrics[std::size_t(v)].addPlane(n, -n.dot(P[std::size_t(f[0])]), 0.5 * len);
    }
}

/// The input as the first pass takes it. Rebuilt rather than kept for a possible rerun: a copy
/// would hold ~100 bytes per input vertex for the whole run (about 1.3 GB on a mandible).
State startState(const InterfaceComplex& input, std::size_t corners, const InputMeasures& measures) {
    State st;
    st.points = &input.surface.vertices;
    st.input = &measures.surface;
    st.tris = input.surface.triangles;
    st.sides = input.sides;
    st.pts.resize(st.tris.size());
    st.quadrics.resize(corners);
    st.err.assign(input.surface.vertices.size(), 0.0f);
    st.settled.assign(input.surface.vertices.size(), 0);
    placeCarriedVertices(input, st);
    st.nearTeeth = measures.nearTeeth;
    st.plateMm = &measures.plateMm;
    st.spentMm = &input.sampleErrorMm;
    addTriangleQuadrics(st);
    return st;
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

/// The output's sizes, errors, angles and wedges (the rest of SimplifyStats is the caller's).
SimplifyStats measureOutput(const InterfaceComplex& input, const InterfaceComplex& out, const State& st,
                            const InputMeasures& measures, double minWedgeDeg) {
    SimplifyStats s;
    const auto& plateMm = measures.plateMm;
    s.plateVertices = std::size_t(std::count_if(plateMm.begin(), plateMm.end(), [](float x) { return std::isfinite(x); }));
    s.inputTriangles = input.surface.triangles.size();
    s.outputTriangles = out.surface.triangles.size();
    s.outputVertices = out.surface.vertices.size();
    s.maxErrorMm = st.err.empty() ? 0.0 : double(*std::max_element(st.err.begin(), st.err.end()));
    for (std::size_t v = 0; v < st.err.size(); ++v)
        if (measures.nearTeeth[v]) s.maxErrorNearTeethMm = std::max(s.maxErrorNearTeethMm, double(st.err[v]));
    s.minAngleDeg = 180;
    const double bins[] = {5, 10, 15, 20, 30, 40};
    for (std::size_t t = 0; t < out.surface.triangles.size(); ++t) {
        const Tri& f = out.surface.triangles[t];
        const double a = minAngleDeg(out.surface.vertices[f[0]], out.surface.vertices[f[1]], out.surface.vertices[f[2]]);
        s.minAngleDeg = std::min(s.minAngleDeg, a);
        s.minAngleHistogram[std::size_t(std::upper_bound(std::begin(bins), std::end(bins), a) - std::begin(bins))]++;
        s.trianglesPerKind[interfaceKind(out.sides[t][0], out.sides[t][1])]++;
    }
    const RegionWedgeStats wedges = measureRegionWedges(out, minWedgeDeg);
    s.minWedgeDeg = wedges.smallestDeg;
    s.edgesBelowMinWedge = wedges.edgesBelow;
    return s;
}

}  // namespace

InterfaceComplex simplifyInterfaces(const InterfaceComplex& input, const SimplifyOptions& options,
                                    Progress& progress, SimplifyStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    checkInputArrays(input);
    checkOptions(options);
    const std::size_t corners = checkedCorners(input);
    ProgressStage stage(progress, "simplify interfaces");
    const InputMeasures measures = measureInput(input, options);
    State st = startState(input, corners, measures);
    std::size_t collapses = simplify::simplifyInPasses(st, options, progress, stage);
    // The corners split first, so the exact check below is of the very surface handed on (the
    // tet stage of a run relies on it instead of checking again).
    InterfaceComplex out = complexOf(st, input.surface.vertices);
    std::size_t cornerSplits = splitThreeTriangleCorners(out);  // forced slivers (SplitCorners.h)
    SelfIntersectionReport check = findSelfIntersections(out.surface);
    bool rerun = false;
    if (!check.pairs.empty() && !options.exhaustiveIntersectionChecks) {
        // The local test missed two sheets meeting away from the collapse: start again with the
        // exhaustive test (slower, but every collapse is then checked against everything).
        st = startState(input, corners, measures);
        SimplifyOptions exhaustive = options;
        exhaustive.exhaustiveIntersectionChecks = true;
        collapses = simplify::simplifyInPasses(st, exhaustive, progress, stage);
        out = complexOf(st, input.surface.vertices);
        cornerSplits = splitThreeTriangleCorners(out);
        check = findSelfIntersections(out.surface);
        rerun = true;
    }
    if (!check.clean())
        throw Error("simplification: the output has " + std::to_string(check.pairs.size()) + " intersecting triangle pairs and " +
                    std::to_string(check.degenerate.size()) +
                    " degenerate triangles (the input surface must be intersection-free)");
    SimplifyStats local;
    SimplifyStats& s = stats ? *stats : local;
    // Both only read the output (the statistics are serial, the seeds' rays mostly parallel).
    std::vector<RegionSeed> seeds;
    tbb::parallel_invoke([&] { seeds = seedsInsideShells(out); },  // grid seeds may have left a thin region (ShellSeeds.h)
                         [&] { s = measureOutput(input, out, st, measures, options.minWedgeDeg); });
    out.seeds = std::move(seeds);
    s.exhaustiveRerun = rerun;
    s.cornerSplits = cornerSplits;
    s.collapses = collapses;
    s.seconds = secondsSince(start);
    return out;
}

}  // namespace jawmesh
