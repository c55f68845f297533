// Components of tets apart from the interface triangles (union-find over shared faces), each labeled
// by the sides of the triangles that bound it; then the tets of the outside dropped.
#include "tet/LabelFromSides.h"

#include "io/Error.h"
#include "tet/InterfaceTriangleIndex.h"
#include "tet/TetFaceAdjacency.h"
#include "tet/TetStageName.h"
#include "tet/UnusedNodes.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace jawmesh {
namespace {

/// Per tet, the smallest tet of its component: tets are joined across every face shared by two of
/// them that is neither an input triangle nor one of TetGen's subfaces.
std::vector<std::int32_t> componentRoots(const TetFaceAdjacency& adj, std::size_t tets, const InterfaceTriangleIndex& triangleOf,
                                         const std::vector<std::array<std::int32_t, 3>>& facets) {
    std::vector<std::int32_t> parent(tets);
    for (std::size_t t = 0; t < tets; ++t) parent[t] = std::int32_t(t);
    const auto find = [&](std::int32_t x) {
        while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
        return x;
    };
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        if (adj.groupSize(g) != 2) continue;
        const auto& f0 = adj.faces[std::size_t(adj.groupStart[g])];
        if (triangleOf.contains(f0.key) || std::binary_search(facets.begin(), facets.end(), f0.key)) continue;
        const std::int32_t a = find(f0.tet), b = find(adj.faces[std::size_t(adj.groupStart[g]) + 1].tet);
        if (a != b) parent[std::size_t(std::max(a, b))] = std::min(a, b);
    }
    std::vector<std::int32_t> root(tets);
    for (std::size_t t = 0; t < tets; ++t) root[t] = find(std::int32_t(t));
    return root;
}

constexpr Label kUnset = -1;

/// Per component root, the label its bounding input triangles give it (kUnset: none bounds it).
/// Throws when two of them disagree.
std::vector<Label> componentLabels(const InterfaceComplex& plc, const TetMesh& m, const TetFaceAdjacency& adj,
                                   const InterfaceTriangleIndex& triangleOf, const std::vector<std::int32_t>& root) {
    std::vector<Label> component(m.tets.size(), kUnset);
    for (const TetFaceRef& f : adj.faces) {
        const std::size_t input = triangleOf.find(f.key);
        if (input == InterfaceTriangleIndex::npos) continue;
        const Tri& tri = plc.surface.triangles[input];
        // on the normal side unless the triangle is wound as the tet's outward face (exact: the
        // raw tets can be flat)
        const bool front = !sameWinding(tri, outwardFace(m.tets[std::size_t(f.tet)], f.local));
        const Label side = plc.sides[input][front ? 0 : 1];
        Label& c = component[std::size_t(root[std::size_t(f.tet)])];
        if (c == kUnset) c = side;
        if (c == side) continue;
        const auto& v = plc.surface.vertices;
        const Vec3 p = (v[std::size_t(tri[0])] + v[std::size_t(tri[1])] + v[std::size_t(tri[2])]) / 3.0;
        throw Error(kTetStageName, "the tets next to interface triangle " + std::to_string(input) + " near (" + tetgenNumber(p.x()) +
                               ", " + tetgenNumber(p.y()) + ", " + tetgenNumber(p.z()) +
                               ") belong to a component that other triangles give " + labelName(c) + ", but this one gives " +
                               labelName(side) + ": a region boundary is open (TetGen lost a facet?)");
    }
    return component;
}

}  // namespace

void labelFromSides(const InterfaceComplex& plc, TetgenMesh& raw) {
    TetMesh& m = raw.mesh;
    const InterfaceTriangleIndex triangleOf = interfaceTriangleIndex(plc);
    const TetFaceAdjacency adj = tetFaceAdjacency(m);
    const std::vector<std::int32_t> root = componentRoots(adj, m.tets.size(), triangleOf, raw.facets);
    const std::vector<Label> component = componentLabels(plc, m, adj, triangleOf, root);
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        const Label c = component[std::size_t(root[t])];
        if (c == kUnset) throw Error(kTetStageName, "a group of tets touches no interface triangle (TetGen kept a hull region)");
        m.labels[t] = c;
    }
}

/// Drops unlabeled tets, then the nodes no tet uses (tet/UnusedNodes.h), keeping the order of both.
std::size_t keepLabeled(TetMesh& m) {
    std::size_t kept = 0;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        if (m.labels[t] == kOutsideLabel) continue;
        m.tets[kept] = m.tets[t];
        m.labels[kept++] = m.labels[t];
    }
    const std::size_t removed = m.tets.size() - kept;
    m.tets.resize(kept);
    m.labels.resize(kept);
    dropUnusedNodes(m);
    return removed;
}

}  // namespace jawmesh
