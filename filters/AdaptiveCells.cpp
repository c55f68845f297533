// Implements filters/AdaptiveCells.h; what it computes, its rules and its contract are documented there.
#include "filters/AdaptiveCells.h"

#include "filters/AdaptiveBlockChoice.h"
#include "filters/RegionWedges.h"
#include "filters/SelfIntersections.h"
#include "filters/TriangleGeometry.h"
#include "io/Angles.h"
#include "io/Error.h"
#include "io/ResourceUsage.h"
#include "io/VertexTriangles.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

namespace jawmesh {
namespace {

using openvdb::Coord;

using adaptive::Block;
using adaptive::blockOf;
using adaptive::blocksNearTeeth;
using adaptive::chooseInChildren;
using adaptive::initialBlocks;
using adaptive::kMembersPerBox;
using adaptive::MergeRule;
using adaptive::windowOf;

/// The member whose vertex is nearest the mean of the members' vertices (lowest index on ties).
std::int32_t blockVertex(const Block& b, const std::vector<Vec3>& P) {
    Vec3 mean = Vec3::Zero();
    for (std::int32_t m : b.members) mean += P[std::size_t(m)];
    mean /= double(b.members.size());
    std::int32_t best = b.members.front();
    for (std::int32_t m : b.members)
        if ((P[std::size_t(m)] - mean).squaredNorm() < (P[std::size_t(best)] - mean).squaredNorm()) best = m;
    return best;
}

/// The surface as the blocks make it, built locally: each cell's quads, and per cell its block and
/// the vertex that stands for it. Split blocks stay in `blocks` with no members (ids are stable).
struct Mesh {
    const std::vector<DualQuad>& quads;
    const std::vector<Vec3>& P;
    VertexTriangles quadsOfCell;  ///< per dual cell, the quads it is a corner of
    std::vector<Block> blocks;
    std::vector<std::int32_t> vertexOf, blockOfCell, blockAtVertex;

    /// Lowers d2 (and sets nearest) to the nearest vertex of the cells that vertex v stands for
    /// (its block's members in order, or itself) nearer than d2; stops once d2 <= stop2. The
    /// first nearest in member order, as a plain scan finds it: a box of members at d2 or
    /// farther holds none nearer.
    void nearestInCluster(std::int32_t v, const Vec3& x, double stop2, double& d2, std::int32_t& nearest) const {
        const auto visit = [&](std::int32_t c) {
            const double e = (P[std::size_t(c)] - x).squaredNorm();
            if (e < d2) {
                d2 = e;
                nearest = c;
            }
        };
        const std::int32_t b = blockAtVertex[std::size_t(v)];
        if (b < 0) return visit(v);
        const Block& k = blocks[std::size_t(b)];
        for (std::size_t j = 0; j < k.memberBoxes.size() && d2 > stop2; ++j) {
            if (k.memberBoxes[j].squaredDistance(x) >= d2) continue;
            const std::size_t end = std::min(k.members.size(), (j + 1) * kMembersPerBox);
            for (std::size_t i = j * kMembersPerBox; i < end && d2 > stop2; ++i) visit(k.members[i]);
        }
    }

    /// The quads that make the triangles at vertex v, sorted: its block's rim quads, or a fine
    /// cell's own quads (quadsOfCell lists them in order).
    std::pair<const std::int32_t*, const std::int32_t*> quadsAt(std::int32_t v) const {
        const std::int32_t b = blockAtVertex[std::size_t(v)];
        if (b < 0) return {quadsOfCell.begin(v), quadsOfCell.end(v)};
        const auto& rim = blocks[std::size_t(b)].rimQuads;
        return {rim.data(), rim.data() + rim.size()};
    }

    /// The triangles (with their quads' label pairs) that have both x and y as corners (y = x: all
    /// triangles at x), from the quads of the one of the two with fewer.
    void trianglesAt(std::int32_t x, std::int32_t y, std::vector<Tri>& tris, std::vector<std::array<Label, 2>>& sides) const {
        auto [begin, end] = quadsAt(x);
        if (y != x) {
            const auto [yBegin, yEnd] = quadsAt(y);
            if (yEnd - yBegin < end - begin) begin = yBegin, end = yEnd;
        }
        tris.clear();
        sides.clear();
        for (const std::int32_t* it = begin; it != end; ++it) {
            const std::int32_t q = *it;
            std::array<std::int32_t, 4> v;
            for (int k = 0; k < 4; ++k) v[std::size_t(k)] = vertexOf[std::size_t(quads[std::size_t(q)].cells[std::size_t(k)])];
            Tri t[2];
            const int n = quadTriangles(v, P, t);
            for (int i = 0; i < n; ++i) {
                const bool hasX = t[i][0] == x || t[i][1] == x || t[i][2] == x;
                const bool hasY = t[i][0] == y || t[i][1] == y || t[i][2] == y;
                if (hasX && hasY) {
                    tris.push_back(t[i]);
                    sides.push_back(quads[std::size_t(q)].sides);
                }
            }
        }
    }

    /// Squared distance from x to the fine triangles of the quads around dual cell c, or the
    /// first of them at most `enough` (the callers only ask whether it is over that).
    double squaredDistanceToFineAround(std::int32_t c, const Vec3& x, double enough) const {
        double best = std::numeric_limits<double>::infinity();
        for (const std::int32_t* q = quadsOfCell.begin(c); q != quadsOfCell.end(c); ++q) {
            Tri t[2];
            const int n = quadTriangles(quads[std::size_t(*q)].cells, P, t);
            for (int i = 0; i < n; ++i) {
                best = std::min(best, squaredDistanceToTriangle(x, P[std::size_t(t[i][0])], P[std::size_t(t[i][1])],
                                                                P[std::size_t(t[i][2])]));
                if (best <= enough) return best;
            }
        }
        return best;
    }

    /// Makes block b the one its members belong to (a new block or a live one).
    void assign(std::size_t b) {
        Block& k = blocks[b];
        if (k.vertex < 0) k.vertex = blockVertex(k, P);
        for (std::int32_t c : k.members) {
            blockOfCell[std::size_t(c)] = std::int32_t(b);
            vertexOf[std::size_t(c)] = k.vertex;
        }
        blockAtVertex[std::size_t(k.vertex)] = std::int32_t(b);
    }
    /// Block b is gone: its cells are fine again (until a child takes them).
    void release(std::size_t b) {
        Block& k = blocks[b];
        std::vector<std::int32_t>().swap(k.rimQuads);
        std::vector<BBox>().swap(k.memberBoxes);
        for (std::int32_t c : k.members) {
            blockOfCell[std::size_t(c)] = -1;
            vertexOf[std::size_t(c)] = c;
        }
        blockAtVertex[std::size_t(k.vertex)] = -1;
    }
};

/// Per-thread scratch of the certificate.
struct Scratch {
    std::vector<Tri> fan, edgeTris;
    std::vector<std::array<Label, 2>> fanSides, edgeSides;
    std::vector<EdgeFanTriangle> wedge;
    std::vector<std::pair<std::int32_t, std::int32_t>> edges;
    std::vector<std::pair<std::int32_t, std::int32_t>> sampledEdges;  ///< fan edges whose midpoint is measured
    std::vector<std::pair<Vec3, double>> spheres;  ///< per fan triangle: centre and radius, mm
};

/// The wedge of every region at edge a-b, from the triangles `tris` (sides `sides`) that have both.
double edgeWedgeDeg(const std::vector<Vec3>& P, std::int32_t a, std::int32_t b, const std::vector<Tri>& tris,
                    const std::vector<std::array<Label, 2>>& sides, std::vector<EdgeFanTriangle>& wedge) {
    wedge.clear();
    for (std::size_t j = 0; j < tris.size(); ++j) {
        const Tri& g = tris[j];
        int ia = 0, ib = 0;
        for (int k = 0; k < 3; ++k) {
            if (g[std::size_t(k)] == a) ia = k + 1;
            if (g[std::size_t(k)] == b) ib = k + 1;
        }
        if (!ia || !ib) continue;
        const bool aThenB = ib - 1 == ia % 3;
        wedge.push_back({P[std::size_t(g[std::size_t(3 - (ia - 1) - (ib - 1))])], sides[j][0], sides[j][1], aThenB});
    }
    return smallestRegionWedgeDeg(P[std::size_t(a)], P[std::size_t(b)], wedge.data(), wedge.size(), FanKind::Whole);
}

/// No triangle at the block's vertex x has an angle under the minimum or an edge longer than its
/// interface allows (the simplification only bounds the edges it makes), and no region spans a
/// wedge under the minimum at their edges: the simplification could not always remove such shapes,
/// and TetGen under -Y must keep them (slivers). The triangles at a spoke x-y are the fan's own;
/// those at a rim edge are looked up. Each edge is measured once.
bool fanShapeOk(const Mesh& mesh, std::int32_t x, Scratch& s, double cosMinAngle, double minWedgeDeg,
                const InterfaceBounds& bounds) {
    const auto& P = mesh.P;
    s.edges.clear();
    for (std::size_t i = 0; i < s.fan.size(); ++i) {
        const Tri& f = s.fan[i];
        if (smallestAngleCosine(P[std::size_t(f[0])], P[std::size_t(f[1])], P[std::size_t(f[2])]) > cosMinAngle) return false;
        const double maxEdge = bounds.maxEdgeMm(s.fanSides[i][0], s.fanSides[i][1]);
        for (int k = 0; k < 3; ++k) {
            const std::int32_t a = f[std::size_t(k)], b = f[std::size_t((k + 1) % 3)];
            if ((P[std::size_t(a)] - P[std::size_t(b)]).squaredNorm() > maxEdge * maxEdge) return false;
            s.edges.push_back({std::min(a, b), std::max(a, b)});
        }
    }
    std::sort(s.edges.begin(), s.edges.end());
    s.edges.erase(std::unique(s.edges.begin(), s.edges.end()), s.edges.end());
    for (const auto& [a, b] : s.edges) {
        double wedge;
        if (a == x || b == x) {
            wedge = edgeWedgeDeg(P, a, b, s.fan, s.fanSides, s.wedge);
        } else {
            mesh.trianglesAt(a, b, s.edgeTris, s.edgeSides);
            wedge = edgeWedgeDeg(P, a, b, s.edgeTris, s.edgeSides, s.wedge);
        }
        if (wedge < minWedgeDeg) return false;
    }
    return true;
}

/// The block's fine vertices from its triangles (each carried by the nearest) and the triangles'
/// sample points from the fine surface: fills carriers and both errors; false when one exceeds
/// its bound (mm). Stops early then.
bool errorsWithin(Block& b, const Mesh& mesh, Scratch& s, double carriedMm, double sampleMm) {
    const auto& P = mesh.P;
    const auto corner = [&](const Tri& t, int k) -> const Vec3& { return P[std::size_t(t[std::size_t(k)])]; };
    double worst2 = 0;
    b.carrier.assign(b.members.size(), -1);
    if (s.fan.empty()) return false;  // no triangle carries the members
    // each fan triangle's bounding sphere: one farther than the nearest so far is not looked at
    s.spheres.clear();
    for (const Tri& t : s.fan) {
        const Vec3 c = (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0;
        const double r2 = std::max({(corner(t, 0) - c).squaredNorm(), (corner(t, 1) - c).squaredNorm(), (corner(t, 2) - c).squaredNorm()});
        s.spheres.push_back({c, std::sqrt(r2)});
    }
    const auto distance2 = [&](const Vec3& x, std::size_t t) {
        return squaredDistanceToTriangle(x, corner(s.fan[t], 0), corner(s.fan[t], 1), corner(s.fan[t], 2));
    };
    for (std::size_t i = 0; i < b.members.size(); ++i) {
        const Vec3& x = P[std::size_t(b.members[i])];
        // The previous member's carrier first (members are near each other): its distance prunes
        // most of the fan at once. The nearest is still the lowest-indexed of the nearest.
        const std::int32_t guess = i > 0 ? b.carrier[i - 1] : 0;
        double d2 = distance2(x, std::size_t(guess)), d = std::sqrt(d2);
        b.carrier[i] = guess;  // index into the fan; made a triangle id at the end
        for (std::size_t t = 0; t < s.fan.size(); ++t) {
            if (std::int32_t(t) == guess) continue;
            const auto& [centre, radius] = s.spheres[t];
            const double reach = (d + radius) * (1.0 + 1e-9);  // a margin over rounding: the same nearest
            if ((x - centre).squaredNorm() > reach * reach) continue;
            const double e = distance2(x, t);
            if (e < d2 || (e == d2 && std::int32_t(t) < b.carrier[i])) {
                d2 = e;
                d = std::sqrt(e);
                b.carrier[i] = std::int32_t(t);
            }
        }
        worst2 = std::max(worst2, d2);
        if (worst2 > carriedMm * carriedMm) return false;
    }
    b.carriedErrorMm = float(std::sqrt(worst2));
    worst2 = 0;
    s.sampledEdges.clear();
    for (const Tri& t : s.fan) {
        const Vec3 a = corner(t, 0), c1 = corner(t, 1), c2 = corner(t, 2);
        const Vec3 samples[4] = {(a + c1 + c2) / 3.0, 0.5 * (a + c1), 0.5 * (c1 + c2), 0.5 * (c2 + a)};
        for (int k = 0; k < 4; ++k) {
            const Vec3& x = samples[k];
            // A spoke's midpoint is shared by two fan triangles: measured once, from the clusters
            // of the first one's corners (a distance to part of the fine surface, as any is).
            if (k > 0) {
                const std::pair<std::int32_t, std::int32_t> e = std::minmax(t[std::size_t(k - 1)], t[std::size_t(k % 3)]);
                if (std::find(s.sampledEdges.begin(), s.sampledEdges.end(), e) != s.sampledEdges.end()) continue;
                s.sampledEdges.push_back(e);
            }
            // Only a sample farther than every one so far raises the error: a fine vertex within
            // that distance ends its search.
            double d2 = std::numeric_limits<double>::infinity();
            std::int32_t nearest = -1;
            for (std::int32_t v : t) mesh.nearestInCluster(v, x, worst2, d2, nearest);
            // a fine triangle within worst2 settles it as a fine vertex does
            if (d2 > worst2) d2 = std::min(d2, mesh.squaredDistanceToFineAround(nearest, x, worst2));
            worst2 = std::max(worst2, d2);
            if (worst2 > sampleMm * sampleMm) return false;
        }
    }
    b.sampleErrorMm = float(std::sqrt(worst2));
    return true;
}

/// The live blocks that share a quad with a cell of block b (their triangles change with b's).
void neighbourBlocks(const Mesh& mesh, const Block& b, std::vector<char>& mark) {
    for (std::int32_t c : b.members)
        for (const std::int32_t* q = mesh.quadsOfCell.begin(c); q != mesh.quadsOfCell.end(c); ++q)
            for (std::int32_t d : mesh.quads[std::size_t(*q)].cells) {
                const std::int32_t o = mesh.blockOfCell[std::size_t(d)];
                if (o >= 0) mark[std::size_t(o)] = 1;
            }
}

/// Blocks at a self-intersecting or degenerate triangle of `triangles` (exact check). Only pairs
/// with a triangle not in `checked` (sorted: the triangles of the last check that were in no
/// intersecting pair) are tested; `checked` becomes those of this check.
std::vector<std::int32_t> blocksAtIntersections(const std::vector<Tri>& triangles, const Mesh& mesh,
                                                std::vector<Tri>& checked) {
    SurfaceMesh surface;
    std::vector<std::int32_t> id(mesh.P.size(), -1);
    surface.triangles = triangles;
    for (Tri& t : surface.triangles)
        for (std::int32_t& c : t) {
            if (id[std::size_t(c)] < 0) {
                id[std::size_t(c)] = std::int32_t(surface.vertices.size());
                surface.vertices.push_back(mesh.P[std::size_t(c)]);
            }
            c = id[std::size_t(c)];
        }
    std::vector<char> isNew(triangles.size(), 1);
    if (!checked.empty())
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 4096), [&](const auto& r) {
            for (std::size_t t = r.begin(); t != r.end(); ++t)
                isNew[t] = !std::binary_search(checked.begin(), checked.end(), triangles[t]);
        });
    const SelfIntersectionReport report = findSelfIntersections(surface, checked.empty() ? nullptr : &isNew);
    // the triangles found in a pair stay unchecked: one may come back unchanged after the split
    std::vector<char> found(triangles.size(), 0);
    for (const auto& [a, b] : report.pairs) found[std::size_t(a)] = found[std::size_t(b)] = 1;
    for (std::int32_t t : report.degenerate) found[std::size_t(t)] = 1;
    checked.clear();
    for (std::size_t t = 0; t < triangles.size(); ++t)
        if (!found[t]) checked.push_back(triangles[t]);
    tbb::parallel_sort(checked.begin(), checked.end());
    std::vector<std::int32_t> hit;
    const auto mark = [&](std::int32_t t) {
        for (std::int32_t c : triangles[std::size_t(t)])
            if (mesh.blockAtVertex[std::size_t(c)] >= 0) hit.push_back(mesh.blockAtVertex[std::size_t(c)]);
    };
    for (const auto& [a, b] : report.pairs) {
        mark(a);
        mark(b);
    }
    for (std::int32_t t : report.degenerate) mark(t);
    std::sort(hit.begin(), hit.end());
    hit.erase(std::unique(hit.begin(), hit.end()), hit.end());
    return hit;
}

/// The quads around every dual cell, in compressed rows.
VertexTriangles quadsOfCells(const std::vector<DualQuad>& quads, std::size_t cellCount) {
    VertexTriangles rows;
    rows.start.assign(cellCount + 1, 0);
    for (const DualQuad& q : quads)
        for (std::int32_t c : q.cells) ++rows.start[std::size_t(c) + 1];
    for (std::size_t c = 0; c < cellCount; ++c) rows.start[c + 1] += rows.start[c];
    rows.list.resize(rows.start[cellCount]);
    std::vector<std::uint32_t> at(rows.start.begin(), rows.start.end() - 1);
    for (std::size_t q = 0; q < quads.size(); ++q)
        for (std::int32_t c : quads[q].cells) rows.list[at[std::size_t(c)]++] = std::int32_t(q);
    return rows;
}

/// The rim quads of blocks [first, end) (Block::rimQuads), in parallel: each quad once, from its
/// lowest cell among the members; none with every cell a member (it makes no triangle). Fixed
/// while the block lives: its members decide them, not its neighbours. (Scanning every member's
/// quads at each look-up instead cost 1.2 of the 22 s of the shared mandible's adaptive stage.)
void findRimQuads(Mesh& mesh, std::size_t first) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, mesh.blocks.size(), 64), [&](const auto& r) {
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
            Block& k = mesh.blocks[b];
            k.rimQuads.clear();
            for (std::int32_t c : k.members)
                for (const std::int32_t* q = mesh.quadsOfCell.begin(c); q != mesh.quadsOfCell.end(c); ++q) {
                    bool lowest = true, inside = true;
                    for (std::int32_t d : mesh.quads[std::size_t(*q)].cells) {
                        const bool member = mesh.blockOfCell[std::size_t(d)] == std::int32_t(b);
                        lowest = lowest && !(member && d < c);
                        inside = inside && member;
                    }
                    if (lowest && !inside) k.rimQuads.push_back(*q);
                }
            std::sort(k.rimQuads.begin(), k.rimQuads.end());
        }
    });
}

/// The member boxes of blocks [first, end) (Block::memberBoxes), in parallel; fixed while the
/// block lives. They let a sample's nearest member skip most of a block (the certification's
/// hottest loop scanned every member of three clusters for each sample).
void boxMembers(Mesh& mesh, std::size_t first) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(first, mesh.blocks.size(), 64), [&](const auto& r) {
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
            Block& k = mesh.blocks[b];
            k.memberBoxes.clear();
            for (std::size_t i = 0; i < k.members.size(); i += kMembersPerBox) {
                BBox box;
                const std::size_t end = std::min(k.members.size(), i + kMembersPerBox);
                for (std::size_t j = i; j < end; ++j) box.extend(mesh.P[std::size_t(k.members[j])]);
                k.memberBoxes.push_back(box);
            }
        }
    });
}

}  // namespace

nlohmann::json toJson(const AdaptiveStats& s) {
    return {{"fine_cells", s.fineCells},
            {"blocks", s.blocks},
            {"far_bone_blocks", s.farBoneBlocks},
            {"cells_merged", s.cellsMerged},
            {"split_for_error", s.splitForError},
            {"split_for_intersection", s.splitForIntersection},
            {"rounds", s.rounds},
            {"max_carried_error_mm", s.maxCarriedErrorMm},
            {"max_sample_error_mm", s.maxSampleErrorMm},
            {"seconds", s.seconds}};
}

namespace {

/// What the certification needs besides the mesh.
struct CertifyRule {
    const AdaptiveOptions& options;
    int top;                                     ///< the largest level
    openvdb::BoolGrid::ConstAccessor nearTeeth;  ///< top-level blocks near a tooth or PDL
    double cosMinAngle;
};

/// The dirty blocks (with members) whose fan fails its shape or error test, in block order.
std::vector<std::size_t> failingBlocks(Mesh& mesh, const std::vector<char>& dirty, const CertifyRule& rule) {
    std::vector<std::size_t> todo;
    for (std::size_t b = 0; b < mesh.blocks.size(); ++b)
        if (dirty[b] && !mesh.blocks[b].members.empty()) todo.push_back(b);
    std::vector<char> failed(todo.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 64), [&](const auto& r) {
        Scratch s;
        auto nearAcc = rule.nearTeeth;  // accessors are per thread
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            Block& k = mesh.blocks[todo[i]];
            mesh.trianglesAt(k.vertex, k.vertex, s.fan, s.fanSides);
            // a block above the top level is far from the teeth (initialBlocks)
            const bool nearTeeth = k.level <= rule.top && nearAcc.isValueOn(blockOf(k.lo, rule.top - k.level));
            const double bound = rule.options.bounds.boundMm(k.sides[0], k.sides[1], nearTeeth);
            failed[i] = !fanShapeOk(mesh, k.vertex, s, rule.cosMinAngle, rule.options.minWedgeDeg, rule.options.bounds) ||
                        !errorsWithin(k, mesh, s, rule.options.carriedFraction * bound, rule.options.sampleFraction * bound);
        }
    });
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < todo.size(); ++i)
        if (failed[i]) out.push_back(todo[i]);
    return out;
}

/// Splits the `split` blocks into their certified children (or back to fine cells when `toFine`);
/// their children and the blocks around them are marked dirty. The children are chosen in
/// parallel (they depend on the labels alone), then put in place in the order of `split`.
void splitBlocks(Mesh& mesh, const std::vector<std::size_t>& split, bool toFine, const openvdb::Int32Grid& labels,
                 const std::vector<Coord>& cells, const MergeRule& rule, std::vector<char>& dirty) {
    std::vector<std::vector<Block>> children(split.size());
    if (!toFine)
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, split.size(), 16), [&](const auto& r) {
            const auto acc = labels.getConstAccessor();
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const Block& b = mesh.blocks[split[i]];
                chooseInChildren(windowOf(acc, b.lo, b.level, rule), cells, b.lo, b.level, rule, b.members, children[i]);
            }
        });
    const std::size_t firstNew = mesh.blocks.size();
    for (std::size_t i = 0; i < split.size(); ++i) {
        const std::size_t b = split[i];
        neighbourBlocks(mesh, mesh.blocks[b], dirty);
        mesh.release(b);
        mesh.blocks[b].members.clear();
        for (Block& c : children[i]) {
            mesh.blocks.push_back(std::move(c));
            mesh.assign(mesh.blocks.size() - 1);
        }
        dirty.resize(mesh.blocks.size(), 1);  // new children are checked
    }
    findRimQuads(mesh, firstNew);
    boxMembers(mesh, firstNew);
    for (std::size_t b : split) dirty[b] = 0;
}

/// The carried cells of every merged block, by the emitted triangle that carries them, and the
/// sample error of every fan's corners; counts the blocks in `st`.
void collectCarried(Mesh& mesh, std::size_t cellCount, int top, AdaptiveSurface& out, AdaptiveStats& st) {
    out.sampleErrorMm.assign(cellCount, 0.0f);
    bool anyBlock = false;
    for (const Block& k : mesh.blocks) anyBlock = anyBlock || !k.members.empty();
    if (!anyBlock) return;
    const VertexTriangles around = vertexTriangles(out.triangles, cellCount);
    out.carried.assign(out.triangles.size(), {});
    // per block, in parallel: the emitted triangle of each fan triangle (the fan as certified, in
    // trianglesAt's order); then the members go to their carriers in block order
    std::vector<std::vector<std::int32_t>> emittedOf(mesh.blocks.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.blocks.size(), 256), [&](const auto& r) {
        Scratch s;
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
            const Block& k = mesh.blocks[b];
            if (k.members.empty()) continue;
            mesh.trianglesAt(k.vertex, k.vertex, s.fan, s.fanSides);
            std::vector<std::int32_t>& emitted = emittedOf[b];
            emitted.assign(s.fan.size(), -1);
            for (std::size_t i = 0; i < s.fan.size(); ++i)
                for (const std::int32_t* t = around.begin(k.vertex); t != around.end(k.vertex); ++t)
                    if (out.triangles[std::size_t(*t)] == s.fan[i]) emitted[i] = *t;
        }
    });
    for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
        const Block& k = mesh.blocks[b];
        if (k.members.empty()) continue;
        const std::vector<std::int32_t>& emitted = emittedOf[b];
        if (std::find(emitted.begin(), emitted.end(), -1) != emitted.end())
            throw Error("adaptive surface: internal error: a certified fan triangle was not emitted");
        for (std::size_t i = 0; i < k.members.size(); ++i)
            if (k.members[i] != k.vertex) out.carried[std::size_t(emitted[std::size_t(k.carrier[i])])].push_back(k.members[i]);
        for (const std::int32_t t : emitted)
            for (std::int32_t c : out.triangles[std::size_t(t)])
                out.sampleErrorMm[std::size_t(c)] = std::max(out.sampleErrorMm[std::size_t(c)], k.sampleErrorMm);
        ++st.blocks;
        st.farBoneBlocks += k.level > top;
        st.cellsMerged += k.members.size();
        st.maxCarriedErrorMm = std::max(st.maxCarriedErrorMm, double(k.carriedErrorMm));
        st.maxSampleErrorMm = std::max(st.maxSampleErrorMm, double(k.sampleErrorMm));
    }
}

}  // namespace

AdaptiveSurface adaptiveSurface(const openvdb::Int32Grid& labels, const std::vector<Coord>& cells, const std::vector<DualQuad>& quads,
                                const std::vector<Vec3>& P, const AdaptiveOptions& options, Progress& progress,
                                AdaptiveStats* stats) {
    const auto start = std::chrono::steady_clock::now();
    AdaptiveStats local;
    AdaptiveStats& st = stats ? *stats : local;
    st = AdaptiveStats{};
    st.fineCells = cells.size();
    const int top = std::clamp(options.maxLevel, 0, 5);
    const MergeRule merge{options.ringVoxels, options.layerGapVoxels};
    Mesh mesh{quads, P, {}, {}, {}, {}, {}};
    mesh.vertexOf.resize(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) mesh.vertexOf[c] = std::int32_t(c);
    mesh.blockOfCell.assign(cells.size(), -1);
    mesh.blockAtVertex.assign(cells.size(), -1);
    AdaptiveSurface out;
    const double voxelMm = labels.voxelSize()[0];
    openvdb::BoolGrid::Ptr near = openvdb::BoolGrid::create(false);
    const int farTop = top > 0 ? std::min(top + options.farBoneExtraLevels, 5) : 0;
    if (top > 0) {
        // both serial and independent
        tbb::parallel_invoke(
            [&] { near = blocksNearTeeth(quads, cells, top, voxelMm * double(1 << top), options.boneNearTeethMm); },
            [&] { mesh.quadsOfCell = quadsOfCells(quads, cells.size()); });
        mesh.blocks = initialBlocks(labels, cells, top, farTop, merge, *near);
        // the blocks' members are disjoint, so are their writes
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.blocks.size(), 256), [&](const auto& r) {
            for (std::size_t b = r.begin(); b != r.end(); ++b) mesh.assign(b);
        });
        findRimQuads(mesh, 0);
        boxMembers(mesh, 0);
    }
    progress.checkCancelled();

    const CertifyRule rule{options, top, near->getConstAccessor(), std::cos(radians(options.minAngleDeg))};
    std::vector<char> dirty(mesh.blocks.size(), 1);
    std::vector<Tri> checked;  // the triangles of the last intersection check, sorted
    // Certify what changed until every block passes; then the exact intersection check of the
    // whole surface, whose blocks go back to fine cells; until it is clean.
    for (int round = 0;; ++round) {
        std::vector<std::size_t> split = failingBlocks(mesh, dirty, rule);
        std::fill(dirty.begin(), dirty.end(), 0);
        st.splitForError += split.size();
        bool toFine = round >= 64;  // a safety net: rounds end long before
        if (split.empty()) {
            emitQuadTriangles(quads, mesh.vertexOf, P, out.triangles, out.sides);
            if (mesh.blocks.empty()) break;
            const std::vector<std::int32_t> hit = blocksAtIntersections(out.triangles, mesh, checked);
            if (hit.empty()) break;
            split.assign(hit.begin(), hit.end());
            st.splitForIntersection += split.size();
            toFine = true;  // no second try for a block at an intersection
        }
        ++st.rounds;
        splitBlocks(mesh, split, toFine, labels, cells, merge, dirty);
        progress.checkCancelled();
    }
    collectCarried(mesh, cells.size(), top, out, st);
    st.seconds = secondsSince(start);
    return out;
}

}  // namespace jawmesh
