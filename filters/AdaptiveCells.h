// Adaptive surface nets: where the fine interface is simple, one vertex stands for a whole block of
// dual cells, so the surface is made coarse there directly instead of being made fine and thrown
// away by the simplification (issue #22: 27 M fine triangles on the shared mandible, 99 % discarded).
//
// Blocks (filters/CoarseBlocks.h) of up to 2^maxLevel dual cells per side are tried largest first;
// one whose labels show a single disc of one interface, with no other sheet or label within
// ringVoxels of it (so thin plates and junction curves stay fine), becomes one vertex: the fine
// vertex of the block nearest the mean of its fine vertices, so every output vertex still lies on the
// fine interface. A block that two parallel sheets cross (a layer such as the PDL, CoarseBlocks.h)
// becomes one vertex per sheet, each standing for the cells of its sheet and certified on its own.
// The quads of the fine surface then join the blocks' vertices (DualQuads.h): a
// vertex identification on a conforming mesh, so the result is conforming (no cracks between block
// sizes), and the disc test keeps it a manifold of the same topology.
//
// Each block is then certified against the fine surface, both ways, against a share of its
// interface's bound (InterfaceBounds.h):
//  - every fine vertex of the block lies within carriedFraction of the bound of the block vertex's
//    triangles; it is handed on, "carried" by its nearest such triangle, and the simplification
//    tracks its distance exactly from then on, like the vertices it removes itself;
//  - the centroid and edge midpoints of every triangle at a block vertex lie within sampleFraction
//    of the bound of the fine surface (the fine vertices of the blocks at its corners, then the fine
//    triangles around the nearest of them: a distance to part of the fine surface, never an
//    underestimate); the simplification spends only the rest of its bound on that direction there.
// Nor may a block make a triangle thinner than minAngleDeg or a region wedge under minWedgeDeg
// (filters/RegionWedges.h), shapes that would reach TetGen as slivers.
// A block that fails is split into its eight children (tested again), and the blocks around it are
// certified again (their triangles changed); a block at a self-intersecting or degenerate triangle of
// the result (exact check once every block passes: of the whole surface the first time, then of the
// pairs with a triangle that changed) goes back to fine cells; until the surface is clean. Fine
// cells alone are the fine extraction, which is clean.
#pragma once

#include "filters/DualQuads.h"
#include "filters/InterfaceBounds.h"
#include "io/Progress.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace jawmesh {

struct AdaptiveOptions {
    /// Largest block: 2^maxLevel dual cells per side (3: 8 voxels, 0.4 mm at 0.05 mm); 0 = off,
    /// at most 5 (the block tests take a block and its ring as rows of 64 bits).
    int maxLevel = 3;
    /// Bone / outside blocks farther than boneNearTeethMm from the teeth may be this many levels
    /// larger (0 to 2; at most level 5 in all).
    int farBoneExtraLevels = 1;
    InterfaceBounds bounds;        ///< per interface (set from the simplification's options)
    double boneNearTeethMm = 2.0;  ///< bone / outside nearer a tooth or PDL gets the near bound
    /// Shares of the interface's bound a block may use: its fine vertices from its triangles, and
    /// its triangles' sample points from the fine surface (the latter is spent for good: a corner
    /// keeps only the rest of the bound for the simplification). Larger shares make larger blocks
    /// and leave the simplifier less to do but less room (docs/DESIGN.md, "Adaptive surface nets":
    /// 0.5 / 0.25 gave the shared mandible's simplifier 2.48 M triangles and 242 k out; 0.9 / 0.5
    /// 1.51 M and 260 k, the run 111 -> 92 s).
    double carriedFraction = 0.9;
    double sampleFraction = 0.5;
    /// Shape: no triangle at a block vertex with an angle under minAngleDeg, no region spanning
    /// less than minWedgeDeg around their edges (RegionWedges.h; set from the simplification's).
    double minAngleDeg = 5.0;
    double minWedgeDeg = 20.0;
    /// No other sheet and no third label within this many voxels of a block (thin plates, junctions).
    /// 1 keeps plates of up to about two voxels and the voxels at junction curves fine; 2 also keeps
    /// both sheets of a four-voxel PDL fine (many more triangles for the simplification); 0 lets
    /// blocks reach a junction, whose tets the improver may not lift over the target.
    int ringVoxels = 1;
    /// Layers (CoarseBlocks.h): a region at least this many voxels thick between two others, such
    /// as the PDL, may have both its sheets merged in one block, a vertex each; 0 = off (both
    /// sheets of a four-voxel PDL stay at level 1: 2.3 M of the mandible's 3.3 M triangles).
    int layerGapVoxels = 2;
};

struct AdaptiveStats {
    std::size_t fineCells = 0;        ///< dual cells of the fine extraction (its vertices)
    std::size_t blocks = 0;           ///< merged blocks in the result
    std::size_t farBoneBlocks = 0;    ///< of them, above maxLevel (AdaptiveOptions::farBoneExtraLevels)
    std::size_t cellsMerged = 0;      ///< fine dual cells that they stand for
    std::size_t splitForError = 0;    ///< blocks split because the certificate failed
    std::size_t splitForIntersection = 0;  ///< blocks dropped at a self-intersection or degenerate triangle
    std::size_t rounds = 0;           ///< rounds of certifying what changed (and checking intersections)
    double maxCarriedErrorMm = 0;     ///< largest distance of a fine vertex from its carrying triangle
    double maxSampleErrorMm = 0;      ///< largest distance of a block triangle's sample from the fine surface
    double seconds = 0;
};

nlohmann::json toJson(const AdaptiveStats& stats);

/// The adaptive surface over dual cell indices: a merged block's vertex cell is a corner, its other
/// cells are carried by triangles.
struct AdaptiveSurface {
    std::vector<Tri> triangles;                 ///< corners are dual cell indices
    std::vector<std::array<Label, 2>> sides;
    std::vector<std::vector<std::int32_t>> carried;  ///< per triangle: the fine cells it stands for
    /// Per dual cell: the largest sample error (second bullet above) of the block triangles at it.
    std::vector<float> sampleErrorMm;
};

/// Merges blocks of the fine dual cells `cells` (vertex positions P, one per cell, from the labels
/// `labels`) where certified, as described above, and emits the triangles of `quads`. With
/// maxLevel 0 this is the fine extraction. Deterministic whatever the thread count.
AdaptiveSurface adaptiveSurface(const openvdb::Int32Grid& labels, const std::vector<openvdb::Coord>& cells, const std::vector<DualQuad>& quads,
                                const std::vector<Vec3>& P, const AdaptiveOptions& options, Progress& progress,
                                AdaptiveStats* stats = nullptr);

}  // namespace jawmesh
