// Sliver improvement on a written mesh: reads a Gmsh .msh (e.g. a run's volumetric mesh), runs
// improveSlivers and prints what it did, so its effect and cost can be measured on real output.
#include "filters/TriangleGeometry.h"
#include "io/GmshReader.h"
#include "io/GmshWriter.h"
#include "tet/ElementQuality.h"
#include "tet/TetFaceAdjacency.h"
#include "tet/ImproveSlivers.h"
#include "tet/ValidateTetMesh.h"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_improve_slivers <mesh.msh> [target-deg] [max-passes] [lookahead-depth] [deep-lookahead-trials] [interface-push-mm]\n");
        return 2;
    }
    jawmesh::TetMesh mesh = jawmesh::readGmsh(argv[1]);
    jawmesh::SliverOptions o;
    if (argc > 2) o.targetMinDihedralDeg = std::stod(argv[2]);
    if (argc > 3) o.maxPasses = std::stoi(argv[3]);
    if (argc > 4) o.lookaheadDepth = std::stoi(argv[4]);
    if (argc > 5) o.deepLookaheadTrials = std::size_t(std::stoul(argv[5]));
    if (argc > 6) o.interfacePushMm = std::stod(argv[6]);
    const jawmesh::ValidationReport before = jawmesh::validateTetMesh(mesh, {});
    const auto volumesBefore = jawmesh::labelVolumesMm3(mesh);  // the improver must keep them
    jawmesh::SliverStats s;
    jawmesh::improveSlivers(mesh, o, &s);
    for (const auto& [label, v] : jawmesh::labelVolumesMm3(mesh))
        if (std::abs(v - volumesBefore.at(label)) > 1e-9 * volumesBefore.at(label))
            std::printf("  VOLUME of label %d changed: %.9f -> %.9f mm^3\n", label, volumesBefore.at(label), v);
    const auto faces = [](const jawmesh::ValidationReport& v) {
        std::size_t n = 0;
        for (const auto& kv : v.interfaceFacesPerPair) n += kv.second;
        return n;
    };
    const jawmesh::ValidationReport r = jawmesh::validateTetMesh(mesh, {});
    if (const char* out = std::getenv("BENCH_OUT")) jawmesh::writeGmsh(mesh, out);  // the improved mesh, for inspection
    std::printf("| %s | below %.0f deg: %zu -> %zu | min dihedral %.2f -> %.2f deg | smoothed %zu, 2-3 %zu, 3-2 %zu, removals %zu, "
                "splits %zu+%zu, stars %zu, interface insertions %zu, lookaheads %zu, pushes %zu (largest %.4f mm), %d passes | %.1f s | violations %zu, interface faces %zu -> %zu (split by interface insertions) |\n",
                argv[1], o.targetMinDihedralDeg, s.badBefore, s.badAfter, s.minDihedralBeforeDeg, s.minDihedralAfterDeg,
                s.smoothed, s.flips23, s.flips32, s.edgeRemovals, s.splits, s.faceSplits, s.cavityStars, s.interfaceInsertions, s.lookaheads, s.interfacePushes, s.largestPushMm, s.passes, s.seconds, r.violationCount(),
                faces(before), faces(r));
    // What is left: per remaining bad tet, how many of its nodes and faces lie on an interface.
    const jawmesh::TetFaceAdjacency adj = jawmesh::tetFaceAdjacency(mesh);
    std::set<std::int32_t> onInterface;
    std::map<std::int32_t, int> interfaceFacesOf;
    std::map<std::int32_t, double> worstInterfaceAngleOf;  // smallest triangle angle of its interface faces
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        const auto& f0 = adj.faces[std::size_t(adj.groupStart[g])];
        if (jawmesh::insideOneRegion(adj, mesh, g)) continue;
        onInterface.insert(f0.key.begin(), f0.key.end());
        const double angle = jawmesh::minAngleDeg(mesh.nodes[std::size_t(f0.key[0])], mesh.nodes[std::size_t(f0.key[1])],
                                                  mesh.nodes[std::size_t(f0.key[2])]);
        for (std::size_t i = std::size_t(adj.groupStart[g]); i < std::size_t(adj.groupStart[g + 1]); ++i) {
            interfaceFacesOf[adj.faces[i].tet]++;
            auto [it, fresh] = worstInterfaceAngleOf.emplace(adj.faces[i].tet, angle);
            if (!fresh) it->second = std::min(it->second, angle);
        }
    }
    std::map<std::pair<int, int>, int> kinds;  // (interface nodes, interface faces) -> count
    std::map<jawmesh::Label, int> byLabel;
    const bool list = std::getenv("BENCH_LIST") != nullptr;  // print every remaining bad tet
    std::map<int, int> byFaceAngle;  // smallest interface-face angle, 5-degree bins (-1: no interface face)
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const auto& e = mesh.tets[t];
        const auto sh = jawmesh::tetShape(mesh.nodes[std::size_t(e[0])], mesh.nodes[std::size_t(e[1])], mesh.nodes[std::size_t(e[2])],
                                          mesh.nodes[std::size_t(e[3])]);
        if (sh.minDihedralDeg >= o.targetMinDihedralDeg) continue;
        if (list) {
            const auto c = (mesh.nodes[std::size_t(e[0])] + mesh.nodes[std::size_t(e[1])] + mesh.nodes[std::size_t(e[2])] +
                            mesh.nodes[std::size_t(e[3])]) / 4.0;
            std::printf("  bad tet %zu label %d min dihedral %.2f at (%.2f, %.2f, %.2f), %d interface faces\n", t, mesh.labels[t],
                        sh.minDihedralDeg, c.x(), c.y(), c.z(), interfaceFacesOf[std::int32_t(t)]);
        }
        int nodes = 0;
        for (auto v : e) nodes += int(onInterface.count(v));
        kinds[{nodes, interfaceFacesOf[std::int32_t(t)]}]++;
        byLabel[mesh.labels[t] < 100 ? 1 : mesh.labels[t] < 200 ? 100 : 200]++;
        const auto w = worstInterfaceAngleOf.find(std::int32_t(t));
        byFaceAngle[w == worstInterfaceAngleOf.end() ? -1 : 5 * int(w->second / 5)]++;
    }
    for (const auto& [k, n] : kinds) std::printf("  left: %d tets with %d interface nodes, %d interface faces\n", n, k.first, k.second);
    for (const auto& [a, n] : byFaceAngle)
        if (a < 0) std::printf("  left: %d tets without an interface face\n", n);
        else std::printf("  left: %d tets whose worst interface face has its smallest angle in [%d, %d) deg\n", n, a, a + 5);
    for (const auto& [l, n] : byLabel) std::printf("  left in %s: %d\n", l == 1 ? "bone" : l == 100 ? "teeth" : "pdl", n);
    return 0;
}
