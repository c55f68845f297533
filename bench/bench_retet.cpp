// Re-tetrahedralizes a written mesh's interface surface with other TetGen options: the interface
// complex (every face between two labels or on the outside, seeds inside every shell) is read back
// from a run's volumetric .msh, so sizing and quality options can be compared on real output
// (e.g. the shared mandible) without repeating extraction and simplification. A TetGen .poly (the
// surface a failed run keeps in failed_surface/) is read as it is, with its own seeds.
// Usage: bench_retet <mesh.msh | surface.poly> [key=value ...], keys: q (radius-edge), dihedral, tgdihedral (TetGen's own), bone, tooth, pdl,
// max (edge mm), O (optimisation level), repair (attempts), improve (0/1), check (0: no intersection check first), Y (0: TetGen may split interface triangles),
// refine (rounds of local refinement, tet/RefineComplex.h), holes (1: only fill the surface's holes and list them),
// trials (the sliver improver's lookahead trials in all), push, outerpush, finalpush (mm an interface node inside the mesh / on its outer boundary / inside the mesh after every rung may be pushed off a thin spot), lost (1: repair the holes, run TetGen once with the first
// rung's switches and list the input triangles that are no tet face), wedges (1: the region wedges before and after the hole repair).
// BENCH_WRITE=<file.msh> writes the mesh.
#include "filters/FillSurfaceHoles.h"
#include "filters/OpenRegionEdges.h"
#include "filters/RegionWedges.h"
#include "filters/ShellSeeds.h"
#include "io/GmshReader.h"
#include "io/GmshWriter.h"
#include "io/Error.h"
#include "io/PolyReader.h"
#include "tet/ElementQuality.h"
#include "tet/LabelFromSides.h"
#include "tet/RegionSurfaces.h"
#include "tet/RepairHoles.h"
#include "tet/TetFaceAdjacency.h"
#include "tet/TetgenAdapter.h"
#include "tet/TetgenGroups.h"
#include "tet/Tetrahedralize.h"
#include "tet/ValidateTetMesh.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>


namespace {

/// lost=1: the input triangles that are no face of any tet of one TetGen run (the first rung's
/// switches, no groups), after the tet stage's hole repair; and whether that run, and the two
/// groups' runs, label from the sides.
int listLostTriangles(const jawmesh::InterfaceComplex& input, const jawmesh::TetOptions& o) {
    const std::vector<double> bounds = jawmesh::seedVolumeBounds(input, o);
    jawmesh::TetStats st;
    jawmesh::InterfaceComplex repaired;
    const jawmesh::InterfaceComplex& c = jawmesh::repairHoles(input, repaired, bounds, st);
    std::printf("repaired: %zu filled, %zu left, %zu triangles\n", st.holeRepair.filled.size(), st.holeRepair.left.size(), c.surface.triangles.size());
    const std::string sw = jawmesh::firstTetgenSwitches(o);
    jawmesh::TetgenMesh raw = jawmesh::runTetgen(c, {sw, jawmesh::kTetgenDefaultOptMaxDihedralDeg, bounds});
    try {
        jawmesh::TetgenMesh labeled = raw;
        jawmesh::labelFromSides(c, labeled);
        std::printf("one run: labeled from the sides\n");
    } catch (const jawmesh::Error& e) { std::printf("one run: %s\n", e.what()); }
    try {
        std::uint64_t peak = 0;
        jawmesh::runTetgenInGroups(c, {sw, jawmesh::kTetgenDefaultOptMaxDihedralDeg, bounds}, true, false, peak);
        std::printf("two groups: labeled from the sides\n");
    } catch (const jawmesh::Error& e) { std::printf("two groups: %s\n", e.what()); }
    const jawmesh::TetFaceAdjacency adj = jawmesh::tetFaceAdjacency(raw.mesh);
    std::set<std::array<std::int32_t, 3>> faces;
    for (const jawmesh::TetFaceRef& f : adj.faces) faces.insert(f.key);
    std::size_t lost = 0;
    for (std::size_t t = 0; t < c.surface.triangles.size(); ++t) {
        std::array<std::int32_t, 3> f = c.surface.triangles[t];
        std::sort(f.begin(), f.end());
        if (faces.count(f)) continue;
        ++lost;
        const auto& v = c.surface.vertices;
        const jawmesh::Vec3 &a = v[std::size_t(f[0])], &b = v[std::size_t(f[1])], &d = v[std::size_t(f[2])];
        const double minEdge = std::min({(a - b).norm(), (b - d).norm(), (d - a).norm()});
        std::printf("lost triangle %zu %s/%s at (%.4f, %.4f, %.4f), shortest edge %.2e mm, area %.2e mm^2, split by TetGen: %s\n", t,
                    jawmesh::labelName(c.sides[t][0]).c_str(), jawmesh::labelName(c.sides[t][1]).c_str(), (a.x() + b.x() + d.x()) / 3,
                    (a.y() + b.y() + d.y()) / 3, (a.z() + b.z() + d.z()) / 3, minEdge, 0.5 * (b - a).cross(d - a).norm(),
                    std::binary_search(raw.facets.begin(), raw.facets.end(), f) ? "no" : "yes or dropped");
    }
    std::printf("%zu of %zu input triangles are no tet face; %zu nodes (%zu input points), %zu tets\n", lost, c.surface.triangles.size(),
                raw.mesh.nodes.size(), c.surface.vertices.size(), raw.mesh.tets.size());
    return 0;
}

/// wedges=1: the region wedges (filters/RegionWedges.h) of the complex as given and after the tet
/// stage's hole repair: a wedge under the dihedral target makes slivers no improver can mend.
int compareRegionWedges(const jawmesh::InterfaceComplex& input, const jawmesh::TetOptions& o) {
    jawmesh::TetStats st;
    jawmesh::InterfaceComplex repaired;
    const jawmesh::InterfaceComplex& c = jawmesh::repairHoles(input, repaired, jawmesh::seedVolumeBounds(input, o), st);
    std::printf("hole repair: %zu filled (%zu cut from tets), %zu left, %zu open edges after\n", st.holeRepair.filled.size(),
                std::size_t(std::count_if(st.holeRepair.filled.begin(), st.holeRepair.filled.end(),
                                          [](const jawmesh::FilledHole& f) { return f.how == jawmesh::HoleRepair::TetCut; })),
                st.holeRepair.left.size(), jawmesh::openRegionEdges(c).size());
    for (const double deg : {5.0, 10.0, 15.0, 20.0}) {
        const jawmesh::RegionWedgeStats a = jawmesh::measureRegionWedges(input, deg), b = jawmesh::measureRegionWedges(c, deg);
        std::printf("edges with a region wedge under %.0f deg: given %zu (smallest %.2f), after the hole repair %zu (smallest %.2f)\n", deg,
                    a.edgesBelow, a.smallestDeg, b.edgesBelow, b.smallestDeg);
        if (deg == 10.0)
            for (const auto& [at, w] : b.below) std::printf("  after the repair: %.2f deg at (%.3f, %.3f, %.3f)\n", w, at.x(), at.y(), at.z());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_retet <mesh.msh> [q=1.5 dihedral=10 bone=2 tooth=1 pdl=0.3 max=0 O=3 repair=2 improve=1]\n");
        return 2;
    }
    jawmesh::TetOptions o;
    bool holesOnly = false;
    bool lostOnly = false, wedgesOnly = false;
    o.boneEdgeMm = 2.0;
    o.toothEdgeMm = 1.0;
    o.pdlEdgeMm = 0.3;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        const auto eq = a.find('=');
        const std::string k = a.substr(0, eq);
        const double v = std::stod(a.substr(eq + 1));
        if (k == "q") o.radiusEdgeRatio = v;
        else if (k == "dihedral") o.slivers.targetMinDihedralDeg = v;
        else if (k == "tgdihedral") o.tetgenMinDihedralDeg = v;
        else if (k == "bone") o.boneEdgeMm = v;
        else if (k == "tooth") o.toothEdgeMm = v;
        else if (k == "pdl") o.pdlEdgeMm = v;
        else if (k == "max") o.maxEdgeMm = v;
        else if (k == "O") o.optimizationLevel = int(v);
        else if (k == "repair") o.repairAttempts = int(v);
        else if (k == "improve") o.improveSlivers = v != 0;
        else if (k == "check") o.checkIntersections = v != 0;
        else if (k == "Y") o.preserveBoundary = v != 0;
        else if (k == "refine") o.refineRounds = int(v);
        else if (k == "holes") holesOnly = v != 0;
        else if (k == "trials") o.slivers.lookaheadTrials = std::size_t(v);
        else if (k == "lost") lostOnly = v != 0;
        else if (k == "wedges") wedgesOnly = v != 0;
        else if (k == "push") o.slivers.interfacePushMm = v;
        else if (k == "outerpush") o.slivers.outerPushMm = v;
        else if (k == "finalpush") o.finalInterfacePushMm = v;
        else { std::fprintf(stderr, "unknown key %s\n", k.c_str()); return 2; }
    }
    const std::string path = argv[1];
    jawmesh::InterfaceComplex c;
    if (path.size() > 5 && path.substr(path.size() - 5) == ".poly") {
        c = jawmesh::readTetgenPoly(path);
    } else {
        const jawmesh::TetMesh in = jawmesh::readGmsh(path);
        // Only the vertices the interface triangles use: the mesh's interior nodes would otherwise go to
        // TetGen as input points and be kept (the counts of session 5 were inflated by them).
        c = jawmesh::meshInterfaces(in);
        c.seeds = jawmesh::seedsInsideShells(c);
    }
    std::printf("input: complex %zu vertices, %zu triangles, %zu seeds\n", c.surface.vertices.size(),
                c.surface.triangles.size(), c.seeds.size());
    if (holesOnly) {  // holes=1: only the hole repair (FillSurfaceHoles.h), every patch listed
        const auto h0 = std::chrono::steady_clock::now();
        const jawmesh::HoleFillStats h = jawmesh::fillSurfaceHoles(c);
        for (const jawmesh::FilledHole& f : h.filled)
            std::printf("%s/%s: %zu edges, %.2f mm, at (%.2f, %.2f, %.2f), %s, %zu triangles\n", jawmesh::labelName(f.pair[0]).c_str(),
                        jawmesh::labelName(f.pair[1]).c_str(), f.boundaryEdges, f.diameterMm, f.centre.x(), f.centre.y(), f.centre.z(),
                        jawmesh::holeRepairName(f.how), f.triangles);
        for (const jawmesh::FilledHole& f : h.left)
            std::printf("left %s/%s: %zu edges, %.2f mm, at (%.2f, %.2f, %.2f)\n", jawmesh::labelName(f.pair[0]).c_str(),
                        jawmesh::labelName(f.pair[1]).c_str(), f.boundaryEdges, f.diameterMm, f.centre.x(), f.centre.y(), f.centre.z());
        std::printf("%zu filled, %zu left, %zu stray edges, %zu open edges after, %.2f s\n", h.filled.size(), h.left.size(), h.strayEdges,
                    jawmesh::openRegionEdges(c).size(), std::chrono::duration<double>(std::chrono::steady_clock::now() - h0).count());
        return 0;
    }
    if (lostOnly) return listLostTriangles(c, o);
    if (wedgesOnly) return compareRegionWedges(c, o);
    jawmesh::TetStats s;
    const auto t0 = std::chrono::steady_clock::now();
    const jawmesh::TetMesh out = jawmesh::tetrahedralize(c, o, jawmesh::noProgress(), &s);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const jawmesh::ValidationReport r = jawmesh::validateTetMesh(out, {});
    std::map<std::string, std::size_t> perKind;
    for (jawmesh::Label l : out.labels) perKind[jawmesh::labelKind(l) == jawmesh::LabelKind::Bone ? "bone" : jawmesh::isToothLike(jawmesh::labelKind(l)) ? "tooth" : "pdl"]++;
    std::printf("| %s | %zu nodes, %zu tets (bone %zu, tooth %zu, pdl %zu) | min dihedral %.2f deg, %zu below %.0f (TetGen %zu) | "
                "%s, %d attempts, %d refinement rounds (%zu edges split) | %.0f s | violations %zu |\n",
                argv[1], out.nodes.size(), out.tets.size(), perKind["bone"], perKind["tooth"], perKind["pdl"], s.minDihedralDeg,
                s.belowMinDihedral, o.slivers.targetMinDihedralDeg, s.slivers.badBefore, s.switches.c_str(), s.attempts, s.refineRounds, s.refinedEdges, sec,
                r.violationCount());
    std::printf("kept run's improver: %zu under the target before, %zu after, %zu lookahead trials%s, %zu pushes (%zu outer), %.1f s\n", s.slivers.badBefore,
                s.slivers.badAfter, s.slivers.lookaheadTrials, s.slivers.lookaheadBudgetSpent ? " (budget spent)" : "",
                s.slivers.interfacePushes, s.slivers.outerPushes, s.slivers.seconds);
    if (s.finalPush)
        std::printf("final push (%.3f mm): %zu under the target before, %zu after, %zu pushes, %.1f s, %s\n", o.finalInterfacePushMm,
                    s.finalPush->badBefore, s.finalPush->badAfter, s.finalPush->interfacePushes, s.finalPush->seconds,
                    s.finalPushKept ? "kept" : "not kept");
    const jawmesh::HoleFillStats& h = s.holeRepair;
    if (!h.filled.empty())
        std::printf("hole repair: %zu holes closed (%zu by a centroid fan), %zu triangles added, %zu removed (lids), largest %.2f mm\n",
                    h.filled.size(), h.verticesAdded(), h.trianglesAdded(), h.trianglesRemoved(), h.largestHoleMm());
    std::map<jawmesh::Label, std::size_t> regions;
    for (jawmesh::Label l : out.labels) regions[l]++;
    std::printf("regions %zu, conformal violations %zu\n", regions.size(), r.violationCount());
    // BENCH_BAD=1: where the tets under the dihedral bound are, and the nearest repaired hole
    if (std::getenv("BENCH_BAD"))
        for (std::size_t t = 0; t < out.tets.size(); ++t) {
            const auto& e = out.tets[t];
            const jawmesh::TetShape sh = jawmesh::tetShape(out.nodes[std::size_t(e[0])], out.nodes[std::size_t(e[1])], out.nodes[std::size_t(e[2])], out.nodes[std::size_t(e[3])]);
            if (sh.minDihedralDeg >= o.slivers.targetMinDihedralDeg) continue;
            const jawmesh::Vec3 c = (out.nodes[std::size_t(e[0])] + out.nodes[std::size_t(e[1])] + out.nodes[std::size_t(e[2])] + out.nodes[std::size_t(e[3])]) / 4.0;
            double best = 1e9;
            const char* how = "-";
            for (const auto& f : h.filled)
                if ((c - f.centre).norm() < best) { best = (c - f.centre).norm(); how = jawmesh::holeRepairName(f.how); }
            std::printf("bad tet %.2f deg at (%.2f, %.2f, %.2f) %s, %.2f mm from a hole (%s)\n", sh.minDihedralDeg, c.x(), c.y(), c.z(),
                        jawmesh::labelName(out.labels[t]).c_str(), best, how);
        }
    // BENCH_WRITE=<file.msh>: keep the mesh (with improve=0, the raw TetGen output that
    // bench_improve_slivers can then be measured on without running TetGen again)
    if (const char* path = std::getenv("BENCH_WRITE")) jawmesh::writeGmsh(out, path);
    return 0;
}
