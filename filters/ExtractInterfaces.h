// Label field -> conformal multi-material interface surface (multi-label surface nets).
//
// For every pair of face-adjacent voxels with different labels the dual quad between them is
// emitted (two triangles), with one vertex per dual cell (2x2x2 voxel block). So every interface
// (tooth/PDL, PDL/bone, bone/outside, ...) appears exactly once and is shared by the two regions it
// separates, and every region's boundary is closed. Junction curves (where three or more regions
// meet) are the edges shared by triangles of different label pairs; they need no extra marking.
//
// Manifoldness: the label grid is first made well-composed (WellComposedLabels.h: diagonal-only
// contacts are joined by relabelling one voxel), which makes one vertex per dual cell enough for
// each region's boundary to be a 2-manifold. The input LabelField is not modified (a copy is).
//
// Vertex placement: each vertex is the mean of the zero crossings, along the crossed edges of its
// dual cell, of (d_a - d_b) for the two regions a, b of each edge (d = signed distance of the
// region; for the outside, the other region's distance alone), then clamped to the cell shrunk by
// `cellMargin` so neighbouring cells can never swap their vertices.
#pragma once

#include "filters/AdaptiveCells.h"
#include "io/InterfaceComplex.h"
#include "io/Progress.h"
#include "levelset/LabelField.h"

#include <nlohmann/json.hpp>

#include <cstddef>

namespace jawmesh {

struct ExtractOptions {
    /// Vertices stay at least this fraction of a voxel inside their dual cell (0 .. 0.5).
    double cellMargin = 0.05;
    /// Join diagonal-only contacts first (see WellComposedLabels.h). When false the labels must
    /// already be well-composed, otherwise Error is thrown.
    bool repairDiagonalContacts = true;
    /// Pockets of outside enclosed by the jaw and smaller than this (mm^3) are filled with the
    /// region around them first (SmallComponents.h); 0 = keep them.
    double maxEnclosedOutsideMm3 = 1.0;
    /// Fragments of a region (components other than its largest) up to this size (mm^3; 0.01 =
    /// 80 voxels of 0.05 mm) go to the region around them (SmallComponents.h); 0 = keep them.
    double maxFragmentMm3 = 0.01;
    /// Find one seed per region component (findRegionSeeds). Off when the caller places seeds
    /// itself, as simplification does (filters/ShellSeeds.h): the segmentation is then wasted.
    bool findSeeds = true;
    /// Blocks of dual cells merged into one vertex where certified (AdaptiveCells.h); maxLevel 0
    /// gives the fine extraction.
    AdaptiveOptions adaptive;
};

/// What extraction changed in the labels before meshing them (recorded in run.json).
struct ExtractStats {
    std::size_t pocketsFilled = 0;       ///< enclosed outside pockets filled (SmallComponents.h)
    std::size_t pocketVoxelsFilled = 0;
    std::size_t fragmentsAbsorbed = 0;   ///< region fragments given to their surroundings
    std::size_t fragmentVoxelsAbsorbed = 0;
    AdaptiveStats adaptive;              ///< the adaptive extraction (AdaptiveCells.h)
};

/// As run.json's "surface" records it: enclosed_outside_pockets_filled {pockets, voxels},
/// region_fragments_absorbed {fragments, voxels} and adaptive (AdaptiveCells.h).
nlohmann::json toJson(const ExtractStats& stats);

/// The labels extraction meshes: a copy of field.labels with diagonal-only contacts repaired
/// (WellComposedLabels.h) and small enclosed outside pockets and region fragments absorbed
/// (SmallComponents.h), as the options ask. Throws Error when field.labels is missing, or has
/// diagonal contacts and the repair is off.
openvdb::Int32Grid::Ptr labelsToExtract(const LabelField& field, const ExtractOptions& options = {},
                                        Progress& progress = noProgress(), ExtractStats* stats = nullptr);

/// Extracts the interface complex of `field`: surface, label pair per triangle (sides[t][0] is the
/// smaller label, so normals point out of the higher label: into the outside, out of teeth into
/// PDL...), and one seed per connected component of every region (findRegionSeeds on the
/// well-composed labels). Deterministic (independent of the thread count).
/// Throws Error when field.labels is missing or the transform is not linear, Cancelled on cancel.
/// Cost: O(voxels next to an interface); memory ~100 bytes per interface quad.
InterfaceComplex extractInterfaces(const LabelField& field, const ExtractOptions& options = {},
                                   Progress& progress = noProgress(), ExtractStats* stats = nullptr);

/// The same, consuming the field: its labels are prepared in place when nothing else holds them,
/// and the distance grids are let go once the vertices are placed (unless seeds are wanted), so
/// they do not add to the extraction's peak memory.
InterfaceComplex extractInterfaces(LabelField&& field, const ExtractOptions& options = {},
                                   Progress& progress = noProgress(), ExtractStats* stats = nullptr);

}  // namespace jawmesh
