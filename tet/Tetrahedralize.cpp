#include "tet/Tetrahedralize.h"

#include "filters/FillSurfaceHoles.h"
#include "filters/OpenRegionEdges.h"
#include "filters/SelfIntersections.h"
#include "io/Error.h"
#include "io/ResourceUsage.h"
#include "tet/ElementQuality.h"
#include "tet/HoleCut.h"
#include "tet/RefineComplex.h"
#include "tet/TetFaceAdjacency.h"

#include <tetgen.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

namespace jawmesh {
namespace {

constexpr const char* kWhat = "tetrahedralize";

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

std::string fmt(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

/// TetGen meshes a complex with a hole as readily as a closed one, and its tets then join the
/// regions on both sides of the hole: found only after the whole run, as an open region boundary
/// of the labelling. Checked first (after the repair below), so the message names the hole.
void rejectOpenRegions(const InterfaceComplex& plc, const HoleFillStats& repair) {
    const std::vector<OpenRegionEdge> open = openRegionEdges(plc);
    if (open.empty()) return;
    std::size_t edges = 0;
    for (std::size_t i = 0; i < open.size(); ++i) edges += i == 0 || open[i].a != open[i - 1].a || open[i].b != open[i - 1].b;
    // name a region rather than the outside (every hole is in both)
    const auto first = std::find_if(open.begin(), open.end(), [](const OpenRegionEdge& e) { return e.label != kOutsideLabel; });
    const OpenRegionEdge& e = first != open.end() ? *first : open[0];
    const Vec3 p = 0.5 * (plc.surface.vertices[std::size_t(e.a)] + plc.surface.vertices[std::size_t(e.b)]);
    throw Error(kWhat, "the interface surface has holes: " + std::to_string(edges) +
                           " edges where a region's boundary stops (the first on the boundary of " + labelName(e.label) +
                           " near (" + fmt(p.x()) + ", " + fmt(p.y()) + ", " + fmt(p.z()) + "); " +
                           std::to_string(repair.filled.size()) + " holes closed, " + std::to_string(repair.left.size()) +
                           " could not be); the regions would mesh into each other");
}

void checkComplex(const InterfaceComplex& plc) {
    const auto& s = plc.surface;
    if (s.triangles.empty()) throw Error(kWhat, "the interface complex has no triangles");
    if (plc.sides.size() != s.triangles.size())
        throw Error(kWhat, "the interface complex has " + std::to_string(plc.sides.size()) + " side pairs for " +
                               std::to_string(s.triangles.size()) + " triangles");
    if (!plc.carried.empty())  // points on no facet, some exactly on one: TetGen may crash on them
        throw Error(kWhat, "the interface complex still carries the adaptive extraction's vertices (simplify it, or withoutCarried)");
    if (plc.seeds.empty()) throw Error(kWhat, "the interface complex has no region seeds");
    const auto nv = static_cast<std::int64_t>(s.vertices.size());
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        for (auto v : s.triangles[t])
            if (v < 0 || v >= nv) throw Error(kWhat, "triangle " + std::to_string(t) + " has a vertex index out of range");
        if (plc.sides[t][0] == plc.sides[t][1])
            throw Error(kWhat, "triangle " + std::to_string(t) + " separates label " + std::to_string(plc.sides[t][0]) +
                                   " from itself");
    }
    for (const auto& seed : plc.seeds) {
        if (seed.label == kOutsideLabel) throw Error(kWhat, "a region seed has the outside label 0");
        if (!seed.point.allFinite()) throw Error(kWhat, "a region seed is not finite");
        labelKind(seed.label);  // throws for unknown labels
    }
}

double regionVolumeBound(Label label, const TetOptions& o) {
    double edge = 0;
    switch (labelKind(label)) {
    case LabelKind::Bone: edge = o.boneEdgeMm; break;
    case LabelKind::Tooth: edge = o.toothEdgeMm; break;
    case LabelKind::Pdl: edge = o.pdlEdgeMm; break;
    default: break;
    }
    return edge > 0 ? tetVolumeForEdge(edge) : -1.0;  // TetGen: <= 0 means no bound
}

/// Fills a TetGen input. tetgenio frees its arrays with delete[], so they are allocated with new[].
void fillInput(const InterfaceComplex& plc, const TetOptions& o, tetgenio& in) {
    const auto& s = plc.surface;
    in.firstnumber = 0;
    in.numberofpoints = static_cast<int>(s.vertices.size());
    in.pointlist = new REAL[3 * s.vertices.size()];
    for (std::size_t i = 0; i < s.vertices.size(); ++i)
        for (int k = 0; k < 3; ++k) in.pointlist[3 * i + static_cast<std::size_t>(k)] = s.vertices[i][k];

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
        e[4] = regionVolumeBound(plc.seeds[r].label, o);
    }
}

/// TetGen 1.5.0 crashes (double free while unwinding from terminatetetgen) instead of throwing
/// when it meets intersecting facets during meshing, so the surface is checked exactly first (filters/SelfIntersections.h: parallel, touching counts).
/// TetGen's own diagnosis (-d) took about 19 s on the shared mandible's 245 k triangles; this
/// takes well under a second.
void rejectSelfIntersections(const InterfaceComplex& plc) {
    const SelfIntersectionReport report = findSelfIntersections(plc.surface);
    if (report.clean()) return;
    const std::int32_t first = report.pairs.empty() ? report.degenerate.front() : report.pairs.front().first;
    Vec3 c = Vec3::Zero();
    for (std::int32_t v : plc.surface.triangles[std::size_t(first)]) c += plc.surface.vertices[std::size_t(v)] / 3.0;
    throw Error(kWhat, "the interface surface intersects itself (" + std::to_string(report.pairs.size()) +
                           " intersecting triangle pairs, " + std::to_string(report.degenerate.size()) +
                           " degenerate triangles; the first near (" + fmt(c.x()) + ", " + fmt(c.y()) + ", " +
                           fmt(c.z()) + "))");
}

struct Attempt {
    std::string switches;
    double optMaxDihedral;  // TetGen's optimisation target for the largest dihedral angle
};

std::string switchesFor(const TetOptions& o, int level, double ratio) {
    std::string sw = "pzQA";
    sw += "q" + fmt(ratio) + "/" + fmt(o.tetgenMinDihedralDeg >= 0 ? o.tetgenMinDihedralDeg : o.minDihedralDeg);
    const bool regional = o.boneEdgeMm > 0 || o.toothEdgeMm > 0 || o.pdlEdgeMm > 0;
    if (regional) sw += "a";
    if (o.maxEdgeMm > 0) sw += "a" + fmt(tetVolumeForEdge(o.maxEdgeMm));
    if (o.preserveBoundary) sw += "Y";
    if (!o.mergeCoplanarFacets) sw += "M";
    sw += "O" + std::to_string(std::clamp(level, 0, 9)) + "/7";
    return sw;
}

/// The raw TetGen result: all nodes, tets with their attribute (label, 0 when unseeded).
struct RawMesh {
    TetMesh mesh;  // labels = attributes, may contain 0
    /// TetGen's subfaces (sorted node triples): the input triangles, and their pieces where TetGen
    /// had to split one despite -Y.
    std::vector<std::array<std::int32_t, 3>> facets;
};

RawMesh runTetgen(const InterfaceComplex& plc, const TetOptions& o, const Attempt& attempt) {
    tetgenio in, out;
    fillInput(plc, o, in);
    tetgenbehavior b;
    std::vector<char> sw(attempt.switches.begin(), attempt.switches.end());
    sw.push_back('\0');
    if (!b.parse_commandline(sw.data())) throw Error(kWhat, "TetGen rejected the switches '" + attempt.switches + "'");
    b.optmaxdihedral = attempt.optMaxDihedral;
    try {
        tetrahedralize(&b, &in, &out);
    } catch (int code) {
        throw Error(kWhat, tetgenReason(code));
    }
    if (out.numberoftetrahedra <= 0) throw Error(kWhat, "TetGen produced no tetrahedra (are the seeds inside the regions?)");
    if (out.numberofcorners != 4) throw Error(kWhat, "TetGen produced elements with " + std::to_string(out.numberofcorners) + " nodes");

    RawMesh raw;
    TetMesh& m = raw.mesh;
    m.nodes.resize(static_cast<std::size_t>(out.numberofpoints));
    for (std::size_t i = 0; i < m.nodes.size(); ++i)
        m.nodes[i] = Vec3(out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]);
    const auto nt = static_cast<std::size_t>(out.numberoftetrahedra);
    m.tets.resize(nt);
    m.labels.assign(nt, kOutsideLabel);
    const int na = out.numberoftetrahedronattributes;
    for (std::size_t t = 0; t < nt; ++t) {
        Tet e;
        for (int k = 0; k < 4; ++k) e[static_cast<std::size_t>(k)] = out.tetrahedronlist[4 * t + static_cast<std::size_t>(k)];
        // Positive orientation decided exactly: without a quality bound TetGen's tets can be flat
        // enough for a rounded determinant to get the sign wrong (the hole patch's run).
        if (orient3dExact(m.nodes[std::size_t(e[0])], m.nodes[std::size_t(e[1])], m.nodes[std::size_t(e[2])], m.nodes[std::size_t(e[3])]) > 0)
            std::swap(e[2], e[3]);
        m.tets[t] = e;
        if (na > 0) {
            const long seed = std::lround(out.tetrahedronattributelist[static_cast<std::size_t>(na) * t]);
            if (seed >= 1 && seed <= static_cast<long>(plc.seeds.size())) m.labels[t] = plc.seeds[static_cast<std::size_t>(seed - 1)].label;
        }
    }
    for (int f = 0; f < out.numberoftrifaces; ++f) {
        std::array<std::int32_t, 3> key = {out.trifacelist[3 * f], out.trifacelist[3 * f + 1], out.trifacelist[3 * f + 2]};
        std::sort(key.begin(), key.end());
        raw.facets.push_back(key);
    }
    std::sort(raw.facets.begin(), raw.facets.end());
    return raw;
}

namespace pipe_io {

template <class T>
void writeAll(int fd, const T* data, std::size_t count) {
    const char* p = reinterpret_cast<const char*>(data);
    std::size_t left = count * sizeof(T);
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) ::_exit(3);
        p += n;
        left -= std::size_t(n);
    }
}

/// Reads the whole of what the child wrote (until it closes its end).
std::vector<char> readAll(int fd) {
    std::vector<char> out;
    char buf[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        out.insert(out.end(), buf, buf + n);
    }
    return out;
}

template <class T>
void take(const std::vector<char>& in, std::size_t& at, T* data, std::size_t count) {
    const std::size_t bytes = count * sizeof(T);
    if (at + bytes > in.size()) throw Error(kWhat, "TetGen's child process sent a truncated mesh");
    std::memcpy(static_cast<void*>(data), in.data() + at, bytes);  // trivially copyable data (Vec3 included)
    at += bytes;
}

}  // namespace pipe_io

/// runTetgen in a child process: TetGen 1.5.0 aborts on some inputs (failed assertions in its
/// facet recovery, seen on a locally refined mandible surface) where it should throw, and an
/// abort must not take the run down. The child (a fork: TetGen is serial, no thread pool is used
/// there) sends the raw mesh back through a pipe; a child that dies or fails gives an Error.
RawMesh runTetgenIsolated(const InterfaceComplex& plc, const TetOptions& o, const Attempt& attempt,
                          std::uint64_t& childPeakBytes) {
    int fds[2];
    if (::pipe(fds) != 0) throw Error(kWhat, "cannot create a pipe for TetGen's child process");
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        throw Error(kWhat, "cannot fork TetGen's child process");
    }
    if (pid == 0) {
        ::close(fds[0]);
        char status = 0;
        std::string message;
        RawMesh raw;
        try {
            raw = runTetgen(plc, o, attempt);
        } catch (const std::exception& e) {
            status = 1;
            message = e.what();
        }
        pipe_io::writeAll(fds[1], &status, 1);
        if (status) {
            const std::uint64_t n = message.size();
            pipe_io::writeAll(fds[1], &n, 1);
            pipe_io::writeAll(fds[1], message.data(), message.size());
        } else {
            const std::uint64_t counts[3] = {raw.mesh.nodes.size(), raw.mesh.tets.size(), raw.facets.size()};
            pipe_io::writeAll(fds[1], counts, 3);
            pipe_io::writeAll(fds[1], raw.mesh.nodes.data(), raw.mesh.nodes.size());
            pipe_io::writeAll(fds[1], raw.mesh.tets.data(), raw.mesh.tets.size());
            pipe_io::writeAll(fds[1], raw.mesh.labels.data(), raw.mesh.labels.size());
            pipe_io::writeAll(fds[1], raw.facets.data(), raw.facets.size());
        }
        ::close(fds[1]);
        ::_exit(0);  // no destructors or atexit handlers of the parent's state
    }
    ::close(fds[1]);
    const std::vector<char> in = pipe_io::readAll(fds[0]);
    ::close(fds[0]);
    int wstatus = 0;
    struct rusage usage {};
    while (::wait4(pid, &wstatus, 0, &usage) < 0 && errno == EINTR) {
    }
    childPeakBytes = std::max(childPeakBytes, std::uint64_t(usage.ru_maxrss) * 1024u);
    if (WIFSIGNALED(wstatus))
        throw Error(kWhat, "TetGen died (signal " + std::to_string(WTERMSIG(wstatus)) + ", " + strsignal(WTERMSIG(wstatus)) +
                               ") with switches '" + attempt.switches + "'");
    if (!WIFEXITED(wstatus) || WEXITSTATUS(wstatus) != 0 || in.empty())
        throw Error(kWhat, "TetGen's child process failed with switches '" + attempt.switches + "'");
    std::size_t at = 0;
    char status = 0;
    pipe_io::take(in, at, &status, 1);
    if (status) {
        std::uint64_t n = 0;
        pipe_io::take(in, at, &n, 1);
        std::string message(n, '\0');
        pipe_io::take(in, at, message.data(), n);
        throw Error(message);
    }
    std::uint64_t counts[3];
    pipe_io::take(in, at, counts, 3);
    RawMesh raw;
    raw.mesh.nodes.resize(counts[0]);
    raw.mesh.tets.resize(counts[1]);
    raw.mesh.labels.resize(counts[1]);
    raw.facets.resize(counts[2]);
    pipe_io::take(in, at, raw.mesh.nodes.data(), counts[0]);
    pipe_io::take(in, at, raw.mesh.tets.data(), counts[1]);
    pipe_io::take(in, at, raw.mesh.labels.data(), counts[1]);
    pipe_io::take(in, at, raw.facets.data(), counts[2]);
    return raw;
}

/// With the boundary preserved (-Y) every input triangle is a tet face, so the tets split into
/// components separated only by input triangles (or the pieces of one TetGen had to split), and
/// each whole input triangle says which label lies on
/// which side (its normal points into sides[0]). Labels come from that, not from TetGen's seed
/// flooding: a seed a rounding error away from a thin region's facet (a PDL fragment at the crest,
/// seen on the shared mandible) would otherwise label the region wrongly. Tets of components on the
/// outside side are labeled kOutsideLabel. Throws when a component's sides disagree (an open
/// region boundary) or a component touches no input triangle.
void labelFromSides(const InterfaceComplex& plc, const std::vector<std::array<std::int32_t, 3>>& facets, TetMesh& m) {
    std::map<std::array<std::int32_t, 3>, std::size_t> triangleOf;
    for (std::size_t t = 0; t < plc.surface.triangles.size(); ++t) {
        auto key = plc.surface.triangles[t];
        std::sort(key.begin(), key.end());
        triangleOf.emplace(key, t);
    }
    const std::size_t nt = m.tets.size();
    std::vector<std::int32_t> parent(nt);
    for (std::size_t t = 0; t < nt; ++t) parent[t] = std::int32_t(t);
    const auto find = [&](std::int32_t x) {
        while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
        return x;
    };
    const TetFaceAdjacency adj = tetFaceAdjacency(m);
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        if (adj.groupSize(g) != 2) continue;
        const auto& f0 = adj.faces[std::size_t(adj.groupStart[g])];
        if (triangleOf.count(f0.key) || std::binary_search(facets.begin(), facets.end(), f0.key)) continue;
        const std::int32_t a = find(f0.tet), b = find(adj.faces[std::size_t(adj.groupStart[g]) + 1].tet);
        if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
    }
    // The label each input-triangle face gives the tet it bounds.
    constexpr Label kUnset = -1;
    std::vector<Label> component(nt, kUnset);
    for (const TetFaceRef& f : adj.faces) {
        const auto it = triangleOf.find(f.key);
        if (it == triangleOf.end()) continue;
        const Tri& tri = plc.surface.triangles[it->second];
        const Vec3& a = plc.surface.vertices[std::size_t(tri[0])];
        // on the normal side unless the triangle is wound as the tet's outward face (exact: the
        // raw tets can be flat)
        const bool front = !sameWinding(tri, outwardFace(m.tets[std::size_t(f.tet)], f.local));
        const Label side = plc.sides[it->second][front ? 0 : 1];
        Label& c = component[std::size_t(find(f.tet))];
        if (c == kUnset) c = side;
        if (c != side) {
            const Vec3 p = (a + plc.surface.vertices[std::size_t(tri[1])] + plc.surface.vertices[std::size_t(tri[2])]) / 3.0;
            throw Error(kWhat, "the tets next to interface triangle " + std::to_string(it->second) + " near (" + fmt(p.x()) + ", " +
                                   fmt(p.y()) + ", " + fmt(p.z()) + ") belong to a component that other triangles give " +
                                   labelName(c) + ", but this one gives " + labelName(side) +
                                   ": a region boundary is open (TetGen lost a facet?)");
        }
    }
    for (std::size_t t = 0; t < nt; ++t) {
        const Label c = component[std::size_t(find(std::int32_t(t)))];
        if (c == kUnset) throw Error(kWhat, "a group of tets touches no interface triangle (TetGen kept a hull region)");
        m.labels[t] = c;
    }
}

/// Drops unlabeled tets and unused nodes (keeping node order).
std::size_t keepLabeled(TetMesh& m) {
    TetMesh kept;
    std::vector<std::int32_t> newIndex(m.nodes.size(), -1);
    std::size_t removed = 0;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        if (m.labels[t] == kOutsideLabel) {
            ++removed;
            continue;
        }
        for (auto v : m.tets[t]) newIndex[static_cast<std::size_t>(v)] = 0;
    }
    std::int32_t next = 0;
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
        if (newIndex[i] < 0) continue;
        newIndex[i] = next++;
        kept.nodes.push_back(m.nodes[i]);
    }
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        if (m.labels[t] == kOutsideLabel) continue;
        Tet e = m.tets[t];
        for (auto& v : e) v = newIndex[static_cast<std::size_t>(v)];
        kept.tets.push_back(e);
        kept.labels.push_back(m.labels[t]);
    }
    m = std::move(kept);
    return removed;
}

/// The holes no local triangulation closed (filters/FillSurfaceHoles.h left them) are patched with
/// tet faces: a quick tetrahedralization of the open complex (no quality bound, in a child
/// process, the convex hull kept so the holes have tets to cut), labeled as tet/HoleCut.h says in a
/// ball around each hole (radius 1.5 diameters, around its loop's centroid). The patch is taken only
/// when each of its faces lies in such a ball: a repair is local or it is not made.
constexpr double kHoleBallPerDiameter = 1.5;  // the ball's radius, in hole diameters
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

void patchHolesFromTets(InterfaceComplex& c, const TetOptions& o, const HoleCutWay& way, HoleFillStats& stats, std::uint64_t& childPeakBytes) {
    const RawMesh raw = runTetgenIsolated(c, o, Attempt{way.switches, 165.0}, childPeakBytes);
    std::vector<HoleBall> balls;
    for (const FilledHole& h : stats.left)
        balls.push_back({h.centre, way.inBalls ? kHoleBallPerDiameter * h.diameterMm : std::numeric_limits<double>::infinity()});
    const HoleCutPatch patch = holeCutPatch(c, raw.mesh, raw.facets, balls, way.sourcesAtTheirDistance);
    if (!patch.local) return;
    std::vector<std::size_t> count(stats.left.size(), 0);
    for (const Tri& t : patch.triangles) {
        const Vec3 p = (raw.mesh.nodes[std::size_t(t[0])] + raw.mesh.nodes[std::size_t(t[1])] + raw.mesh.nodes[std::size_t(t[2])]) / 3.0;
        std::size_t nearest = stats.left.size();
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t h = 0; h < stats.left.size(); ++h) {
            const double d = (p - stats.left[h].centre).norm();
            if (d <= kHoleBallPerDiameter * stats.left[h].diameterMm && d < best) {
                best = d;
                nearest = h;
            }
        }
        if (nearest == stats.left.size()) return;  // not local: leave the complex as it is
        ++count[nearest];
    }
    // TetGen keeps the input points first, in order (-z); its own points are appended.
    const std::size_t inputPoints = c.surface.vertices.size();
    std::map<std::int32_t, std::int32_t> added;
    for (std::size_t i = 0; i < patch.triangles.size(); ++i) {
        Tri t = patch.triangles[i];
        for (auto& v : t) {
            if (std::size_t(v) < inputPoints) continue;
            const auto [it, fresh] = added.emplace(v, std::int32_t(c.surface.vertices.size()));
            if (fresh) c.surface.vertices.push_back(raw.mesh.nodes[std::size_t(v)]);
            v = it->second;
        }
        c.surface.triangles.push_back(t);
        c.sides.push_back(patch.sides[i]);
    }
    for (std::size_t h = 0; h < stats.left.size(); ++h) {
        if (count[h] == 0) continue;
        FilledHole hole = stats.left[h];
        hole.how = HoleRepair::TetCut;
        hole.triangles = count[h];
        stats.filled.push_back(hole);
    }
    stats.left.clear();
}

/// Closes the holes of `input` into `repaired`: local triangulations (filters/FillSurfaceHoles.h),
/// pass after pass while a pass closes something, at most kHoleRepairPasses; then, for what is
/// left, a patch of tet faces (patchHolesFromTets). A hole is a local defect of a surface that
/// took most of the run to make. Returns the complex to mesh: `input` itself when it has no hole.
constexpr int kHoleRepairPasses = 3;
const InterfaceComplex& repairHoles(const InterfaceComplex& input, InterfaceComplex& repaired, const TetOptions& o, TetStats& st) {
    if (openRegionEdges(input).empty()) return input;
    repaired = input;
    HoleFillStats& stats = st.holeRepair;
    const auto fillPasses = [&] {
        for (int pass = 0; pass < kHoleRepairPasses; ++pass) {
            const HoleFillStats more = fillSurfaceHoles(repaired);
            stats.filled.insert(stats.filled.end(), more.filled.begin(), more.filled.end());
            stats.left = more.left;
            stats.strayEdges = more.strayEdges;
            if (more.filled.empty() || (more.left.empty() && more.strayEdges == 0)) break;
        }
    };
    fillPasses();
    if (stats.left.empty() || stats.strayEdges > 0) return repaired;
    const InterfaceComplex filled = repaired;
    const HoleFillStats filledStats = stats;
    for (const HoleCutWay& way : kHoleCutWays) {
        repaired = filled;
        stats = filledStats;
        try {
            patchHolesFromTets(repaired, o, way, stats, st.childPeakMemoryBytes);
        } catch (const Error& e) {
            st.failedAttempts.push_back(std::string("hole patch from tets (") + way.switches + "): " + e.what());
            continue;
        }
        if (!stats.left.empty()) continue;  // not local
        if (!openRegionEdges(repaired).empty()) fillPasses();
        if (openRegionEdges(repaired).empty()) break;
    }
    return repaired;
}

}  // namespace

double tetVolumeForEdge(double edgeMm) { return edgeMm * edgeMm * edgeMm / (6.0 * std::sqrt(2.0)); }

TetMesh tetrahedralize(const InterfaceComplex& input, const TetOptions& options, Progress& progress, TetStats* stats) {
    ProgressStage stage(progress, "tetrahedralize");
    checkComplex(input);
    TetStats st;
    InterfaceComplex repaired;
    const InterfaceComplex& plc = repairHoles(input, repaired, options, st);
    rejectOpenRegions(plc, st.holeRepair);
    if (!(options.radiusEdgeRatio > 1.0)) throw Error(kWhat, "the radius-edge bound must be > 1 (TetGen -q)");
    if (options.minDihedralDeg < 0 || options.minDihedralDeg >= 70)
        throw Error(kWhat, "the minimum dihedral angle must be in [0, 70) degrees");
    if (options.tetgenMinDihedralDeg >= 70)
        throw Error(kWhat, "TetGen's minimum dihedral angle must be below 70 degrees");

    if (options.checkIntersections) rejectSelfIntersections(plc);

    std::vector<Attempt> ladder;
    ladder.push_back({switchesFor(options, options.optimizationLevel, options.radiusEdgeRatio), 165.0});
    // Stronger optimisation: more passes, then a lower target for the largest dihedral (which
    // removes slivers, whose small angles come with angles near 180).
    ladder.push_back({switchesFor(options, std::max(options.optimizationLevel, 7), options.radiusEdgeRatio), 155.0});
    // Last, at most radius-edge 1.5 with TetGen's own dihedral bound: more tets (the mandible
    // 1.30 M instead of 0.99 M at 2/0), kept only when it leaves no tet under the bound where the
    // others did (the one-tooth phantom: 0 instead of 2). Tighter still (1.3, tried before) gave
    // 1.76 M tets and no fewer under 10 degrees.
    TetOptions last = options;
    last.tetgenMinDihedralDeg = -1.0;
    ladder.push_back({switchesFor(last, 9, std::min(options.radiusEdgeRatio, 1.5)), 150.0});
    const std::size_t runs = std::min(ladder.size(), static_cast<std::size_t>(1 + std::max(0, options.repairAttempts)));

    st.inputVertices = input.surface.vertices.size();
    st.inputTriangles = input.surface.triangles.size();
    TetMesh best;
    bool haveBest = false;
    QualityStats bestQuality;
    std::size_t bestAttempt = 0;
    const auto start = std::chrono::steady_clock::now();
    const double stageSteps = static_cast<double>(runs + std::size_t(std::max(0, options.refineRounds)));  // TetGen runs at most
    // One TetGen run on `complex` (in a child process when isolated) with the improver after it;
    // kept when better than the best so far (true). Throws what TetGen or the labelling throws.
    const auto attempt = [&](const InterfaceComplex& complex, std::size_t i, bool lastResort, bool isolated) {
        ++st.attempts;
        RawMesh raw = isolated ? runTetgenIsolated(complex, options, ladder[i], st.childPeakMemoryBytes)
                               : runTetgen(complex, options, ladder[i]);
        if (options.preserveBoundary) labelFromSides(complex, raw.facets, raw.mesh);
        const std::size_t removed = keepLabeled(raw.mesh);
        if (raw.mesh.tets.empty()) throw Error(kWhat, "no tetrahedron received a label: are the seeds inside their regions?");
        SliverStats slivers;
        if (options.improveSlivers) {
            SliverOptions so;
            so.targetMinDihedralDeg = options.minDihedralDeg;
            so.lookaheadDepth = options.sliverLookaheadDepth;
            so.interfacePushMm = options.sliverInterfacePushMm;
            improveSlivers(raw.mesh, so, &slivers, progress);
        }
        const QualityStats q = measureQuality(raw.mesh, options.minDihedralDeg);
        const bool better =
            !haveBest ||
            (lastResort ? q.belowDihedralThreshold == 0 && bestQuality.belowDihedralThreshold > 0
                        : q.belowDihedralThreshold < bestQuality.belowDihedralThreshold ||
                              (q.belowDihedralThreshold == bestQuality.belowDihedralThreshold &&
                               q.minDihedralDeg > bestQuality.minDihedralDeg));
        if (!better) return false;
        best = std::move(raw.mesh);
        bestQuality = q;
        haveBest = true;
        bestAttempt = i;
        st.switches = ladder[i].switches + (ladder[i].optMaxDihedral != 165.0 ? " (optmaxdihedral " + fmt(ladder[i].optMaxDihedral) + ")" : "");
        st.outsideTetsRemoved = removed;
        st.slivers = slivers;
        return true;
    };
    for (std::size_t i = 0; i < runs && !(haveBest && bestQuality.belowDihedralThreshold == 0); ++i) {
        progress.checkCancelled();
        stage.update(static_cast<double>(i) / stageSteps);
        try {
            // The last attempt (radius-edge 1.5 with TetGen's own dihedral bound) makes far more
            // tets (the mandible: 1.3 M): it is kept only when it meets the bound the others missed.
            attempt(plc, i, i > 0 && i + 1 == ladder.size(), false);
        } catch (const Error& e) {
            // A repair run exists only to improve angles: when it fails (TetGen's stronger
            // optimisation has lost a facet on a valid surface), the mesh already made stands.
            if (!haveBest) throw;
            st.failedAttempts.push_back(ladder[i].switches + ": " + e.what());
        }
    }
    // Refinement rounds (RefineComplex.h): the surface edges around the tets still under the bound
    // are split and the kept attempt runs again, while that leaves fewer such tets.
    InterfaceComplex refined;  // the complex of the last kept round
    for (int round = 0; round < options.refineRounds && bestQuality.belowDihedralThreshold > 0; ++round) {
        progress.checkCancelled();
        stage.update(static_cast<double>(runs + std::size_t(round)) / stageSteps);
        InterfaceComplex next = round == 0 ? plc : refined;
        const std::size_t split = splitComplexEdges(next, edgesAroundBadTets(next, best, options.minDihedralDeg));
        if (split == 0) break;
        try {
            if (!attempt(next, bestAttempt, false, true)) break;
        } catch (const Error& e) {
            st.failedAttempts.push_back("refinement round " + std::to_string(round + 1) + ": " + e.what());
            break;
        }
        refined = std::move(next);
        st.refinedEdges += split;
        ++st.refineRounds;
    }
    st.seconds = secondsSince(start);
    st.nodes = best.nodes.size();
    st.tets = best.tets.size();
    st.minDihedralDeg = bestQuality.minDihedralDeg;
    st.maxRadiusEdge = bestQuality.maxRadiusEdge;
    st.belowMinDihedral = bestQuality.belowDihedralThreshold;
    if (stats) *stats = st;
    stage.update(1.0);
    return best;
}

}  // namespace jawmesh
