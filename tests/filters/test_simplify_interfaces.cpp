// Interface simplification on the synthetic jaw: far fewer triangles with every region still
// closed, manifold, of the same topology, within the error bound, intersection-free; deterministic.
#include "filters/ExtractInterfaces.h"
#include "filters/NearTeeth.h"
#include "filters/PlateThickness.h"
#include "filters/RegionWedges.h"
#include "filters/SelfIntersections.h"
#include "filters/SimplifyInterfaces.h"
#include "filters/TriangleBvh.h"
#include "filters/TriangleGeometry.h"
#include "io/Error.h"
#include "io/PolyWriter.h"
#include "support_SyntheticLabels.h"
#include "support_FineExtraction.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <set>

namespace jawmesh {
namespace {

using test::regionLabels;

struct Simplified {
    InterfaceComplex fine, coarse;
    SimplifyStats stats;
};

/// The small phantom's bone is all within the default 2 mm of its tooth: a shorter "near" makes
/// both bone bounds (near and far) apply.
SimplifyOptions phantomOptions() {
    SimplifyOptions o;
    o.boneNearTeethMm = 0.2;
    o.pdlErrorMm = 0.03;  // differs from toothErrorMm, so each interface is held to its own bound
    return o;
}

const Simplified& phantom() {
    static const Simplified s = [] {
        Simplified r;
        r.fine = extractInterfaces(test::jawPhantom(0.05).field, test::fineExtraction());
        r.coarse = simplifyInterfaces(r.fine, phantomOptions(), noProgress(), &r.stats);
        return r;
    }();
    return s;
}

/// The bound of a point of interface (a, b): bone far from the teeth is allowed more.
double boundFor(Label a, Label b, bool nearTeeth, const SimplifyOptions& o) {
    const std::string kind = interfaceKind(a, b);
    if (kind == "tooth/pdl" || kind == "pdl/bone") return o.pdlErrorMm;
    if (kind != "bone/outside") return o.toothErrorMm;
    return nearTeeth ? o.boneErrorMm : std::max(o.boneErrorMm, o.boneFarErrorMm);
}

TEST(SimplifyInterfaces, FewerTrianglesSameRegionsClosedAndIntersectionFree) {
    const auto& s = phantom();
    std::printf("phantom: %zu -> %zu triangles, max error %.4f mm, min angle %.1f deg, %.2f s\n",
                s.fine.surface.triangles.size(), s.coarse.surface.triangles.size(), s.stats.maxErrorMm,
                s.stats.minAngleDeg, s.stats.seconds);
    EXPECT_EQ(s.stats.outputTriangles, s.coarse.surface.triangles.size());
    EXPECT_LT(s.coarse.surface.triangles.size(), s.fine.surface.triangles.size() / 3);
    EXPECT_EQ(regionLabels(s.coarse), regionLabels(s.fine));
    std::set<std::pair<Label, Label>> finePairs, coarsePairs;
    for (const auto& p : s.fine.sides) finePairs.insert({p[0], p[1]});
    for (const auto& p : s.coarse.sides) coarsePairs.insert({p[0], p[1]});
    EXPECT_EQ(coarsePairs, finePairs);
    for (Label L : regionLabels(s.coarse)) EXPECT_EQ(test::checkRegionBoundary(s.coarse, L), "") << labelName(L);
    const auto si = findSelfIntersections(s.coarse.surface);
    EXPECT_TRUE(si.pairs.empty()) << si.pairs.size() << " intersecting pairs";
    EXPECT_TRUE(si.degenerate.empty());
    std::size_t histogram = 0;
    for (auto n : s.stats.minAngleHistogram) histogram += n;
    EXPECT_EQ(histogram, s.coarse.surface.triangles.size());
}

TEST(SimplifyInterfaces, TopologyOfEveryRegionIsKept) {
    const auto& s = phantom();
    for (Label L : regionLabels(s.fine)) {
        const auto before = test::eulerAndComponents(regionBoundary(s.fine, L));
        const auto after = test::eulerAndComponents(regionBoundary(s.coarse, L));
        EXPECT_EQ(after, before) << labelName(L) << " (Euler characteristic, components)";
    }
    // seeds (placed anew on the output) inside their own region's boundary and outside every
    // other region, and every region has one
    std::set<Label> seeded;
    for (const auto& seed : s.coarse.seeds) seeded.insert(seed.label);
    EXPECT_EQ(seeded, regionLabels(s.coarse));
    for (const auto& seed : s.coarse.seeds)
        for (Label L : regionLabels(s.coarse)) {
            const double w = test::windingNumber(regionBoundary(s.coarse, L), seed.point);
            EXPECT_NEAR(w, L == seed.label ? 1.0 : 0.0, 1e-6) << labelName(seed.label) << " seed vs " << labelName(L);
        }
}

/// Both directions of the bound of simplified `s.coarse` against the fine extraction `s.fine`.
void expectWithinBounds(const Simplified& s, const SimplifyOptions& o) {
    EXPECT_LE(s.stats.maxErrorMm, std::max({o.toothErrorMm, o.pdlErrorMm, o.boneErrorMm, o.boneFarErrorMm}) + 1e-9);
    EXPECT_LE(s.stats.maxErrorNearTeethMm, std::max({o.toothErrorMm, o.pdlErrorMm, o.boneErrorMm}) + 1e-9);
    const std::vector<char> near = verticesNearTeeth(s.fine, o.boneNearTeethMm);
    // Both directions, per label pair, brute force on the small phantom: every fine vertex to the
    // coarse triangles of its pair, and the centroid of every coarse triangle to the fine ones.
    std::map<std::pair<Label, Label>, std::vector<std::size_t>> fineBy, coarseBy;
    for (std::size_t t = 0; t < s.fine.sides.size(); ++t) fineBy[{s.fine.sides[t][0], s.fine.sides[t][1]}].push_back(t);
    for (std::size_t t = 0; t < s.coarse.sides.size(); ++t)
        coarseBy[{s.coarse.sides[t][0], s.coarse.sides[t][1]}].push_back(t);
    const auto dist = [](const Vec3& p, const SurfaceMesh& m, const std::vector<std::size_t>& tris) {
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t t : tris) {
            const Tri& f = m.triangles[t];
            best = std::min(best, squaredDistanceToTriangle(p, m.vertices[f[0]], m.vertices[f[1]], m.vertices[f[2]]));
        }
        return std::sqrt(best);
    };
    std::size_t farChecked = 0;
    for (const auto& [pair, fineTris] : fineBy) {
        const double loose = boundFor(pair.first, pair.second, false, o);
        const auto& coarseTris = coarseBy[pair];
        double worstCoarse = 0;
        std::set<int> fineVerts;
        for (std::size_t t : fineTris)
            for (int v : s.fine.surface.triangles[t]) fineVerts.insert(v);
        for (int v : fineVerts) {
            const double d = dist(s.fine.surface.vertices[v], s.coarse.surface, coarseTris);
            const double bound = boundFor(pair.first, pair.second, near[std::size_t(v)] != 0, o);
            if (bound > o.boneErrorMm) ++farChecked;
            EXPECT_LE(d, bound + 1e-9) << labelName(pair.first) << "|" << labelName(pair.second) << " vertex " << v;
            if (d > bound + 1e-9) break;
        }
        for (std::size_t t : coarseTris) {
            const Tri& f = s.coarse.surface.triangles[t];
            const Vec3 c = (s.coarse.surface.vertices[f[0]] + s.coarse.surface.vertices[f[1]] + s.coarse.surface.vertices[f[2]]) / 3;
            worstCoarse = std::max(worstCoarse, dist(c, s.fine.surface, fineTris));
        }
        // the other side per interface: looser at the junction curves, where a coarse triangle of
        // one interface lies over fine triangles of its neighbour (checked below against them all)
        EXPECT_LE(worstCoarse, 1.5 * loose) << labelName(pair.first) << "|" << labelName(pair.second);
    }
    EXPECT_GT(farChecked, 0u) << "the phantom has bone far from its teeth";

    // The other direction against the whole fine surface, at the centroid and edge midpoints of
    // every coarse triangle (where a flat triangle over a curved surface is farthest from it):
    // within the bound of its interface, the tighter one when a corner is near the teeth.
    const TriangleBvh fineBvh = buildTriangleBvh(s.fine.surface);
    const std::vector<char> coarseNear = verticesNearTeeth(s.coarse, o.boneNearTeethMm);
    double worstExcess = -1;
    for (std::size_t t = 0; t < s.coarse.sides.size(); ++t) {
        const Tri& f = s.coarse.surface.triangles[t];
        const Vec3& a = s.coarse.surface.vertices[f[0]];
        const Vec3& b = s.coarse.surface.vertices[f[1]];
        const Vec3& c = s.coarse.surface.vertices[f[2]];
        const bool anyNear = coarseNear[std::size_t(f[0])] || coarseNear[std::size_t(f[1])] || coarseNear[std::size_t(f[2])];
        const double bound = boundFor(s.coarse.sides[t][0], s.coarse.sides[t][1], anyNear, o);
        for (const Vec3& x : {Vec3((a + b + c) / 3), Vec3((a + b) / 2), Vec3((b + c) / 2), Vec3((c + a) / 2)}) {
            const double d = std::sqrt(closestTriangle(fineBvh, x).squaredDistanceMm2);
            worstExcess = std::max(worstExcess, d - bound);
        }
    }
    EXPECT_LE(worstExcess, 1e-9) << "a coarse triangle strays from the fine surface by more than its bound";
}

TEST(SimplifyInterfaces, HausdorffToTheFineInterfaceWithinTheBound) { expectWithinBounds(phantom(), phantomOptions()); }

TEST(SimplifyInterfaces, AdaptiveExtractionThenSimplificationKeepsTheBoundsAgainstTheFineSurface) {
    // The pipeline's path: merged blocks (their fine vertices carried), then the simplification,
    // measured against the fine extraction as the reference.
    const SimplifyOptions o = phantomOptions();
    const LabelField field = test::jawPhantom(0.05).field;
    ExtractOptions adaptive;
    adaptive.adaptive = matchedTo(o);
    ExtractStats extractStats;
    const InterfaceComplex merged = extractInterfaces(field, adaptive, noProgress(), &extractStats);
    ASSERT_GT(extractStats.adaptive.blocks, 0u) << "the phantom has blocks to merge";
    Simplified s;
    s.fine = extractInterfaces(field, test::fineExtraction());
    s.coarse = simplifyInterfaces(merged, o, noProgress(), &s.stats);
    std::printf("phantom: fine %zu, merged %zu (%zu blocks), simplified %zu triangles\n",
                s.fine.surface.triangles.size(), merged.surface.triangles.size(), extractStats.adaptive.blocks,
                s.coarse.surface.triangles.size());
    expectWithinBounds(s, o);
    for (Label L : regionLabels(s.fine)) {
        EXPECT_EQ(test::checkRegionBoundary(s.coarse, L), "") << labelName(L);
        EXPECT_EQ(test::eulerAndComponents(regionBoundary(s.coarse, L)), test::eulerAndComponents(regionBoundary(s.fine, L)))
            << labelName(L) << " (Euler characteristic, components)";
    }
    EXPECT_TRUE(findSelfIntersections(s.coarse.surface).clean());
}

TEST(SimplifyInterfaces, CapKeepsThreeTrianglesAcrossThePdl) {
    // The cap (PDL / outside) is 0.2 mm wide: its edges stay below a third of that, or as they were.
    const auto& s = phantom();
    const SimplifyOptions o = phantomOptions();
    const auto longestCapEdge = [](const InterfaceComplex& c, std::size_t& n) {
        double longest = 0;
        for (std::size_t t = 0; t < c.sides.size(); ++t) {
            if (interfaceKind(c.sides[t][0], c.sides[t][1]) != "pdl/outside") continue;
            ++n;
            const Tri& f = c.surface.triangles[t];
            for (int k = 0; k < 3; ++k)
                longest = std::max(longest, (c.surface.vertices[f[k]] - c.surface.vertices[f[(k + 1) % 3]]).norm());
        }
        return longest;
    };
    std::size_t nFine = 0, nCoarse = 0;
    const double fine = longestCapEdge(s.fine, nFine), coarse = longestCapEdge(s.coarse, nCoarse);
    EXPECT_GT(nCoarse, 0u);
    EXPECT_LE(coarse, std::max(o.capMaxEdgeMm, fine));
    EXPECT_LT(coarse, 0.2 / 2.5);
}

TEST(SimplifyInterfaces, NoRegionComesToSpanAThinWedge) {
    // A wedge under minWedgeDeg caps the dihedral angles of every tet in it: collapses never make
    // the smallest one smaller than the input's or the option's, whichever is less.
    const auto& s = phantom();
    const double bound = phantomOptions().minWedgeDeg;
    const RegionWedgeStats fine = measureRegionWedges(s.fine, bound);
    const RegionWedgeStats coarse = measureRegionWedges(s.coarse, bound);
    std::printf("smallest region wedge: fine %.2f deg (%zu edges under %.0f), simplified %.2f deg (%zu)\n",
                fine.smallestDeg, fine.edgesBelow, bound, coarse.smallestDeg, coarse.edgesBelow);
    EXPECT_GE(coarse.smallestDeg, std::min(bound, fine.smallestDeg) - 1e-9);
    EXPECT_LE(coarse.edgesBelow, fine.edgesBelow);
    EXPECT_DOUBLE_EQ(s.stats.minWedgeDeg, coarse.smallestDeg);
    EXPECT_EQ(s.stats.edgesBelowMinWedge, coarse.edgesBelow);
}

TEST(SimplifyInterfaces, ThinPlatesKeepTheirThicknessAndGetNoLongEdges) {
    // A tooth-labelled slab about 0.08 mm thick (1-2 voxels), gently curved: its sheets may move
    // by a quarter of its thickness at most, and no new edge on it may be longer than 4 times it.
    // Without the plate rules the slab gets the tooth's long edges, so the tets across it would be
    // flat.
    const Label tooth = toothLabel(18);
    const auto slab = [](const Vec3& p) {
        const double mid = 0.05 * std::sin(2.0 * p.x());
        return std::max({std::abs(p.z() - mid) - 0.04, std::abs(p.x()) - 1.0, std::abs(p.y()) - 1.0});
    };
    const auto field = test::sampleField({{tooth, slab}}, {-1, -1, -0.1}, {1, 1, 0.1}, 0.05);
    const InterfaceComplex fine = extractInterfaces(field.field);
    SimplifyOptions on;
    SimplifyOptions off = on;
    off.plateMaxMm = 0;
    SimplifyStats stats;
    const InterfaceComplex coarse = simplifyInterfaces(fine, on, noProgress(), &stats);
    const InterfaceComplex free = simplifyInterfaces(fine, off);

    const std::vector<float> fineT = plateThicknessMm(fine, {});
    float thinnest = std::numeric_limits<float>::infinity(), thickest = 0;
    for (float t : fineT)
        if (std::isfinite(t)) {
            thinnest = std::min(thinnest, t);
            thickest = std::max(thickest, t);
        }
    ASSERT_GT(stats.plateVertices, fine.surface.vertices.size() / 2) << "the slab's faces are a plate";
    const auto inner = [](const Vec3& p) { return std::abs(p.x()) < 0.9 && std::abs(p.y()) < 0.9; };
    const auto longestInnerEdge = [&](const InterfaceComplex& c) {
        double longest = 0;
        for (const Tri& f : c.surface.triangles) {
            const Vec3 &a = c.surface.vertices[f[0]], &b = c.surface.vertices[f[1]], &d = c.surface.vertices[f[2]];
            if (inner(a) && inner(b) && inner(d)) longest = std::max({longest, (a - b).norm(), (b - d).norm(), (d - a).norm()});
        }
        return longest;
    };
    const double edgeOn = longestInnerEdge(coarse), edgeOff = longestInnerEdge(free);
    const std::vector<float> coarseT = plateThicknessMm(coarse, {});
    float coarseThinnest = std::numeric_limits<float>::infinity();
    for (std::size_t v = 0; v < coarseT.size(); ++v)
        if (inner(coarse.surface.vertices[v])) coarseThinnest = std::min(coarseThinnest, coarseT[v]);
    std::printf("slab: plate %.4f-%.4f mm; %zu -> %zu triangles (%zu without the plate rules); longest inner edge %.3f mm (%.3f)\n",
                thinnest, thickest, fine.surface.triangles.size(), coarse.surface.triangles.size(),
                free.surface.triangles.size(), edgeOn, edgeOff);
    EXPECT_LE(edgeOn, on.plateEdgeFactor * thickest + 1e-9);
    EXPECT_GT(edgeOff, on.plateEdgeFactor * thickest);
    EXPECT_GE(coarseThinnest, (1 - 2 * on.plateErrorFraction) * thinnest);
    EXPECT_LT(coarse.surface.triangles.size(), fine.surface.triangles.size() / 2);
}

TEST(SimplifyInterfaces, DeterministicAndRejectsBadOptions) {
    const auto& s = phantom();
    const InterfaceComplex again = simplifyInterfaces(s.fine, phantomOptions());
    EXPECT_EQ(again.surface.triangles, s.coarse.surface.triangles);
    EXPECT_EQ(again.surface.vertices, s.coarse.surface.vertices);
    SimplifyOptions bad;
    bad.minAngleDeg = 75;
    EXPECT_THROW(simplifyInterfaces(s.fine, bad), Error);
    bad = SimplifyOptions{};
    bad.minWedgeDeg = 95;
    EXPECT_THROW(simplifyInterfaces(s.fine, bad), Error);
    bad = SimplifyOptions{};
    bad.toothErrorMm = -1;
    EXPECT_THROW(simplifyInterfaces(s.fine, bad), Error);
    InterfaceComplex broken = s.fine;
    broken.sides.pop_back();
    EXPECT_THROW(simplifyInterfaces(broken), Error);
}

TEST(SimplifyInterfaces, SmallBlocksStayValidAndIndependentOfThreads) {
    // 1.5 mm blocks cut the phantom into several: frozen borders, obstacles and the merge all work.
    const auto& s = phantom();
    SimplifyOptions o;
    o.blockMm = 1.5;
    InterfaceComplex one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = simplifyInterfaces(s.fine, o);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = simplifyInterfaces(s.fine, o);
    }
    EXPECT_EQ(one.surface.triangles, two.surface.triangles);
    // the exhaustive intersection test gives a valid result too
    o.exhaustiveIntersectionChecks = true;
    const InterfaceComplex ex = simplifyInterfaces(s.fine, o);
    EXPECT_TRUE(findSelfIntersections(ex.surface).pairs.empty());
    EXPECT_LT(ex.surface.triangles.size(), s.fine.surface.triangles.size() / 3);
    EXPECT_EQ(one.surface.vertices, two.surface.vertices);
    EXPECT_LT(one.surface.triangles.size(), s.fine.surface.triangles.size() / 3);
    for (Label L : regionLabels(one)) EXPECT_EQ(test::checkRegionBoundary(one, L), "") << labelName(L);
    for (Label L : regionLabels(s.fine))
        EXPECT_EQ(test::eulerAndComponents(regionBoundary(one, L)), test::eulerAndComponents(regionBoundary(s.fine, L))) << labelName(L);
    EXPECT_TRUE(findSelfIntersections(one.surface).pairs.empty());
}

}  // namespace
}  // namespace jawmesh
