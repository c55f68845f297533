// tetgenio in and out (filled with new[]: tetgenio frees with delete[]), TetGen's error codes as
// reasons, and the mesh's way through runForked's pipe.
#include "tet/TetgenAdapter.h"
#include "tet/TetStageName.h"

#include "filters/SelfIntersections.h"
#include "io/ChildProcess.h"
#include "io/Error.h"

#include <tetgen.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace jawmesh {
namespace {


std::string tetgenReason(int code) {
    switch (code) {
    case 1: return "TetGen ran out of memory";
    case 2: return "TetGen hit an internal error (often caused by nearly degenerate input)";
    case 3: return "the interface surface intersects itself (TetGen found intersecting facets)";
    case 4: return "the interface surface has a feature smaller than TetGen's tolerance (very short edge or thin sliver)";
    case 5: return "two interface facets are very close to each other (nearly overlapping)";
    case 10: return "TetGen rejected the input (invalid facet or point data)";
    default: return "TetGen failed with code " + std::to_string(code);
    }
}

// tetgenio frees its arrays with delete[], so they are allocated with new[].

void fillPoints(const SurfaceMesh& s, tetgenio& in) {
    in.numberofpoints = static_cast<int>(s.vertices.size());
    in.pointlist = new REAL[3 * s.vertices.size()];
    for (std::size_t i = 0; i < s.vertices.size(); ++i)
        for (int k = 0; k < 3; ++k) in.pointlist[3 * i + static_cast<std::size_t>(k)] = s.vertices[i][k];
}

void fillFacets(const InterfaceComplex& plc, tetgenio& in) {
    const auto& s = plc.surface;
    in.numberoffacets = static_cast<int>(s.triangles.size());
    in.facetlist = new tetgenio::facet[s.triangles.size()];
    in.facetmarkerlist = new int[s.triangles.size()];
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        tetgenio::facet& f = in.facetlist[t];
        tetgenio::init(&f);
        f.numberofpolygons = 1;
        f.polygonlist = new tetgenio::polygon[1];
        tetgenio::init(&f.polygonlist[0]);
        f.polygonlist[0].numberofvertices = 3;
        f.polygonlist[0].vertexlist = new int[3];
        for (int k = 0; k < 3; ++k) f.polygonlist[0].vertexlist[k] = s.triangles[t][static_cast<std::size_t>(k)];
        in.facetmarkerlist[t] = interfaceMarker(plc.sides[t][0], plc.sides[t][1]);
    }
}

void fillRegions(const InterfaceComplex& plc, const std::vector<double>& volumeBounds, tetgenio& in) {
    if (volumeBounds.size() != plc.seeds.size())
        throw Error(kTetStageName, "internal error: " + std::to_string(volumeBounds.size()) + " volume bounds for " +
                               std::to_string(plc.seeds.size()) + " seeds");
    in.numberofregions = static_cast<int>(plc.seeds.size());
    in.regionlist = new REAL[5 * plc.seeds.size()];
    for (std::size_t r = 0; r < plc.seeds.size(); ++r) {
        REAL* e = in.regionlist + 5 * r;
        e[0] = plc.seeds[r].point.x();
        e[1] = plc.seeds[r].point.y();
        e[2] = plc.seeds[r].point.z();
        // The attribute is the seed's number, not its label: TetGen numbers regions that no seed
        // reaches max(attribute) + 1, ..., which could collide with a real label.
        e[3] = static_cast<REAL>(r + 1);
        e[4] = volumeBounds[r] > 0 ? volumeBounds[r] : -1.0;  // TetGen: <= 0 means no bound
    }
}

void readNodes(const tetgenio& out, TetMesh& m) {
    m.nodes.resize(static_cast<std::size_t>(out.numberofpoints));
    for (std::size_t i = 0; i < m.nodes.size(); ++i)
        m.nodes[i] = Vec3(out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]);
}

/// The tets, oriented positively, labeled from their seed attribute (kOutsideLabel without one).
void readTets(const tetgenio& out, const std::vector<RegionSeed>& seeds, TetMesh& m) {
    const auto nt = static_cast<std::size_t>(out.numberoftetrahedra);
    m.tets.resize(nt);
    m.labels.assign(nt, kOutsideLabel);
    const int na = out.numberoftetrahedronattributes;
    const auto& n = m.nodes;
    for (std::size_t t = 0; t < nt; ++t) {
        Tet e;
        for (int k = 0; k < 4; ++k) e[static_cast<std::size_t>(k)] = out.tetrahedronlist[4 * t + static_cast<std::size_t>(k)];
        // Positive orientation decided exactly: without a quality bound TetGen's tets can be flat
        // enough for a rounded determinant to get the sign wrong (the hole patch's run).
        if (orient3dExact(n[std::size_t(e[0])], n[std::size_t(e[1])], n[std::size_t(e[2])], n[std::size_t(e[3])]) > 0)
            std::swap(e[2], e[3]);
        m.tets[t] = e;
        if (na > 0) {
            const long seed = std::lround(out.tetrahedronattributelist[static_cast<std::size_t>(na) * t]);
            if (seed >= 1 && seed <= static_cast<long>(seeds.size())) m.labels[t] = seeds[static_cast<std::size_t>(seed - 1)].label;
        }
    }
}

std::vector<std::array<std::int32_t, 3>> readFacets(const tetgenio& out) {
    std::vector<std::array<std::int32_t, 3>> facets;
    for (int f = 0; f < out.numberoftrifaces; ++f) {
        std::array<std::int32_t, 3> key = {out.trifacelist[3 * f], out.trifacelist[3 * f + 1], out.trifacelist[3 * f + 2]};
        std::sort(key.begin(), key.end());
        facets.push_back(key);
    }
    std::sort(facets.begin(), facets.end());
    return facets;
}

void sendMesh(ParentPipe& pipe, const TetgenMesh& raw) {
    const std::uint64_t counts[3] = {raw.mesh.nodes.size(), raw.mesh.tets.size(), raw.facets.size()};
    sendToParent(pipe, counts, 3);
    sendToParent(pipe, raw.mesh.nodes.data(), raw.mesh.nodes.size());
    sendToParent(pipe, raw.mesh.tets.data(), raw.mesh.tets.size());
    sendToParent(pipe, raw.mesh.labels.data(), raw.mesh.labels.size());
    sendToParent(pipe, raw.facets.data(), raw.facets.size());
}

TetgenMesh receiveMesh(const std::vector<char>& bytes) {
    std::size_t at = 0;
    std::uint64_t counts[3];
    TetgenMesh raw;
    bool whole = takeFromChild(bytes, at, counts, 3);
    if (whole) {
        raw.mesh.nodes.resize(counts[0]);
        raw.mesh.tets.resize(counts[1]);
        raw.mesh.labels.resize(counts[1]);
        raw.facets.resize(counts[2]);
        whole = takeFromChild(bytes, at, raw.mesh.nodes.data(), counts[0]) && takeFromChild(bytes, at, raw.mesh.tets.data(), counts[1]) &&
                takeFromChild(bytes, at, raw.mesh.labels.data(), counts[1]) && takeFromChild(bytes, at, raw.facets.data(), counts[2]);
    }
    if (!whole) throw Error(kTetStageName, "TetGen's child process sent a truncated mesh");
    return raw;
}

}  // namespace

std::string tetgenNumber(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

TetgenMesh runTetgen(const InterfaceComplex& plc, const TetgenRun& run) {
    tetgenio in, out;
    in.firstnumber = 0;
    fillPoints(plc.surface, in);
    fillFacets(plc, in);
    fillRegions(plc, run.seedVolumeBoundsMm3, in);
    tetgenbehavior b;
    std::vector<char> sw(run.switches.begin(), run.switches.end());
    sw.push_back('\0');
    if (!b.parse_commandline(sw.data())) throw Error(kTetStageName, "TetGen rejected the switches '" + run.switches + "'");
    b.optmaxdihedral = run.optMaxDihedralDeg;
    try {
        tetrahedralize(&b, &in, &out);
    } catch (int code) {
        throw Error(kTetStageName, tetgenReason(code));
    }
    if (out.numberoftetrahedra <= 0) throw Error(kTetStageName, "TetGen produced no tetrahedra (are the seeds inside the regions?)");
    if (out.numberofcorners != 4) throw Error(kTetStageName, "TetGen produced elements with " + std::to_string(out.numberofcorners) + " nodes");
    TetgenMesh raw;
    readNodes(out, raw.mesh);
    readTets(out, plc.seeds, raw.mesh);
    raw.facets = readFacets(out);
    return raw;
}

ForkedChild startTetgenInChild(const InterfaceComplex& plc, const TetgenRun& run) {
    try {
        // TetGen is serial: the child needs no thread pool.
        return startForked([&](ParentPipe& pipe) { sendMesh(pipe, runTetgen(plc, run)); });
    } catch (const Error& e) {
        throw Error(kTetStageName, "TetGen: " + e.reason());
    }
}

TetgenMesh finishTetgenInChild(ForkedChild& child, const TetgenRun& run, std::uint64_t& childPeakBytes) {
    const ForkedResult r = finishForked(child);
    childPeakBytes = std::max(childPeakBytes, r.exit.peakMemoryBytes);
    if (r.exit.signal != 0)
        throw Error(kTetStageName, "TetGen died (signal " + std::to_string(r.exit.signal) + ", " + strsignal(r.exit.signal) +
                               ") with switches '" + run.switches + "'");
    if (r.thrown) throw Error(*r.thrown);
    if (!r.returned) throw Error(kTetStageName, "TetGen's child process failed with switches '" + run.switches + "'");
    return receiveMesh(r.bytes);
}

TetgenMesh runTetgenInChild(const InterfaceComplex& plc, const TetgenRun& run, std::uint64_t& childPeakBytes) {
    ForkedChild child = startTetgenInChild(plc, run);
    return finishTetgenInChild(child, run, childPeakBytes);
}

}  // namespace jawmesh
