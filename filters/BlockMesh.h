// One block's part of the simplification's mesh (SimplifyState.h), in local vertex ids: its
// triangles, the topology queries the collapse tests ask (spokes, fans, neighbours), the bounds
// of each interface, and the collapse itself (apply). Internal to the simplification.
#pragma once

#include "filters/SimplifyInterfaces.h"
#include "filters/SimplifyState.h"
#include "filters/TriangleBoxGrid.h"

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace jawmesh::simplify {

/// One edge u-w seen from u: its triangles (up to a few).
struct Spoke {
    std::int32_t w;
    std::int32_t tris[4];
    int n = 0;
    bool feature = false;  ///< on a junction curve: not two triangles, or two of different label pairs
};

/// A collapse u -> v as the full check (CollapseCheck::plan) accepted it, for BlockMesh::apply.
struct CollapsePlan {
    std::vector<std::int32_t> removed, moved;   // triangles on u-v / the rest of u's fan
    std::int32_t curveOther = -1;               // u's other curve neighbour (curve vertex)
    std::vector<std::pair<std::int32_t, std::int32_t>> assign;  // input vertex -> triangle
    std::vector<float> dist;                    // its distance
    std::vector<std::int32_t> curvePoints;      // points of the merged curve edge v-w
};

/// The block's triangles and vertices. Vertices on the block border (with triangles in other
/// blocks) are frozen: they neither move nor take a collapse (their star is incomplete here).
/// apply() writes err of the block's own vertices straight into `state` (no other block touches
/// them); result() gives everything else back.
struct BlockMesh {
    BlockMesh(State& state, const Block& block, const std::vector<char>& border, const SimplifyOptions& options);

    const SimplifyOptions& opt;
    State& state;
    const std::vector<Vec3>& points;   ///< input vertices (ids of pts and curve points)
    std::vector<std::int32_t> gid;     ///< local vertex -> input vertex id
    std::vector<char> frozen;          ///< per local vertex
    std::vector<Tri> obstacles;        ///< other blocks' triangles, input ids
    std::vector<std::uint64_t> taken;  ///< curve keys copied from the state (owned by this block)
    std::vector<Vec3> pos;             ///< per local vertex
    std::vector<Tri> tri;              ///< local ids
    std::vector<std::array<Label, 2>> sides;
    std::vector<int> pair;             ///< per triangle: interfaceMarker of its sides
    std::vector<char> alive;
    std::vector<std::vector<std::int32_t>> vtris;  ///< per local vertex: its live triangles
    std::vector<std::vector<std::int32_t>> pts;    ///< removed input vertices placed on each triangle
    std::vector<Quadric> q;            ///< per local vertex
    std::vector<char> dead;            ///< per local vertex: collapsed away
    std::unordered_map<std::uint64_t, std::vector<std::int32_t>> curvePts;  ///< per owned curve edge
    std::unordered_map<int, PairRule> rules;  ///< per interfaceMarker
    /// The block's triangles (ids < tri.size()) and obstacles (tri.size() + i); only with
    /// SimplifyOptions::exhaustiveIntersectionChecks.
    TriangleBoxGrid grid;
    double cosTurn = 0.5;              ///< cosine of SimplifyOptions::maxNormalTurnDeg
    double cosMinAngle = 0.94;         ///< cosine of SimplifyOptions::minAngleDeg

    /// Makes the collapse u -> v that CollapseCheck::plan(u, v, plan) accepted just before.
    void apply(std::int32_t u, std::int32_t v, const CollapsePlan& plan);
    /// The block's triangles in input vertex ids; also writes its vertices' quadrics back.
    BlockResult result();

    std::uint64_t gkey(std::int32_t a, std::int32_t b) const { return edgeKey(gid[std::size_t(a)], gid[std::size_t(b)]); }
    /// f in input vertex ids.
    Tri global(Tri f) const {
        for (auto& v : f) v = gid[std::size_t(v)];
        return f;
    }
    const PairRule& rule(std::int32_t t) const { return rules.at(pair[std::size_t(t)]); }
    /// The error bound of input vertex p on triangle t's interface, as a distance from the fine
    /// surface (of which every input vertex is a point: a fine vertex).
    double fineBoundOf(std::int32_t p, std::int32_t t) const;
    /// The same less the sample error the adaptive extraction spent at p (a corner): the bound of
    /// a distance to the input triangles there, which lie that far from the fine surface.
    double boundOf(std::int32_t p, std::int32_t t) const;
    /// How far a thin plate's sheet may move at input vertex p (infinite off plates).
    double plateBound(std::int32_t p) const;
    /// Longest new edge on a thin plate at local vertices a, b, c (infinite off plates).
    double plateEdge(std::int32_t a, std::int32_t b, std::int32_t c) const;

    /// The corner of triangle t other than a and b.
    std::int32_t third(std::int32_t t, std::int32_t a, std::int32_t b) const {
        for (std::int32_t x : tri[std::size_t(t)])
            if (x != a && x != b) return x;
        return -1;
    }
    /// Appends the neighbours of u to out, then sorts out and removes repeats.
    void neighbours(std::int32_t u, std::vector<std::int32_t>& out) const;
    /// The spokes of u, sorted by neighbour id; false when an edge has more than 4 triangles.
    bool spokes(std::int32_t u, std::vector<Spoke>& out) const;
    /// For a vertex without feature edges: true when its triangles form one fan (a disc).
    bool singleFan(std::int32_t u, const std::vector<Spoke>& sp) const;

private:
    void copyTriangles(const Block& block);
    void copyVertices(const std::vector<char>& border);
    void indexTriangles();
    void placeObstacles(const Block& block);
    PairRule ruleFor(Label a, Label b) const;
};

/// The box of a triangle.
inline BBox boxOf(const Vec3& a, const Vec3& b, const Vec3& c) {
    BBox box;
    box.extend(a);
    box.extend(b);
    box.extend(c);
    return box;
}

}  // namespace jawmesh::simplify
