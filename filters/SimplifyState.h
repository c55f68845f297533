// The data the simplification (SimplifyInterfaces.h) hands from pass to pass and from the block
// partition to the block simplifier: plain structs, no behaviour. Internal to the simplification.
#pragma once

#include "filters/Quadric.h"
#include "io/InterfaceComplex.h"
#include "io/VertexTriangles.h"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace jawmesh::simplify {

/// The bounds of one interface (label pair), mm.
struct PairRule {
    double errorMm;     ///< bound for input vertices near a tooth (all of them off bone/outside)
    double maxEdgeMm;
    double farErrorMm;  ///< bound for input vertices far from every tooth
};

/// The input surface around each input vertex, for the distance from new triangles back to it.
struct InputSurface {
    const std::vector<Tri>* tris = nullptr;
    VertexTriangles around;

    explicit InputSurface(const InterfaceComplex& input)
        : tris(&input.surface.triangles), around(vertexTriangles(input.surface.triangles, input.surface.vertices.size())) {}
    /// True when f(t) holds for an input triangle t around input vertex v (stops at the first).
    template <typename F>
    bool anyAround(std::int32_t v, F&& f) const {
        for (const std::int32_t* t = around.begin(v); t != around.end(v); ++t)
            if (f(*t)) return true;
        return false;
    }
};

/// The mesh between passes, in input vertex ids (input vertices never move, so an id is also a
/// position). Triangles carry the input vertices they stand for (their error is tracked).
struct State {
    const std::vector<Vec3>* points = nullptr;   ///< the input vertices
    const InputSurface* input = nullptr;         ///< the input triangles around each input vertex
    std::vector<Tri> tris;
    std::vector<std::array<Label, 2>> sides;
    std::vector<std::vector<std::int32_t>> pts;  ///< per triangle: removed input vertices it carries
    std::vector<Quadric> quadrics;               ///< per input vertex
    std::vector<float> err;                      ///< per input vertex: distance to its output triangle
    std::vector<char> nearTeeth;                 ///< per input vertex (filters/NearTeeth.h)
    const std::vector<float>* plateMm = nullptr; ///< per input vertex: thin plate it bounds (PlateThickness.h)
    /// per corner of the input: error its triangles' samples already have (InterfaceComplex::sampleErrorMm)
    const std::vector<float>* spentMm = nullptr;
    std::unordered_map<std::uint64_t, std::vector<std::int32_t>> curvePts;  ///< per curve edge
    /// per input vertex: every collapse of it was refused in the last pass where it was free, and
    /// no collapse has changed its star since; the next pass tries it only once one does (as a
    /// block does within a pass: the final passes were otherwise spent refusing them all again)
    std::vector<char> settled;
};

/// One block of a pass: its triangles (indices into State::tris) and, for the intersection test
/// only, the triangles of other blocks near it.
struct Block {
    std::vector<std::int32_t> tris;
    std::vector<std::int32_t> obstacles;
};

/// What a block's simplification gives back to be merged into the next State (in input ids).
struct BlockResult {
    std::vector<Tri> tris;
    std::vector<std::array<Label, 2>> sides;
    std::vector<std::vector<std::int32_t>> pts;
    std::vector<std::uint64_t> takenCurves;  ///< curve keys this block owned (replaced by curves)
    std::unordered_map<std::uint64_t, std::vector<std::int32_t>> curves;
    std::vector<std::int32_t> touchedFrozen;  ///< frozen vertices whose star a collapse changed (input ids)
    std::size_t collapses = 0;
};

}  // namespace jawmesh::simplify
