// The simplification's passes (SimplifyInterfaces.h): the live triangles split into cubic blocks,
// every block simplified in parallel by BlockSimplifier.h with its border frozen, the results
// merged in a fixed order. Internal to the simplification.
#pragma once

#include "filters/SimplifyInterfaces.h"
#include "filters/SimplifyState.h"
#include "io/Progress.h"

#include <cstddef>
#include <vector>

namespace jawmesh::simplify {

/// Splits the live triangles of `st` into cubic blocks of blockMm (by centroid, grid shifted by
/// offsetMm), marks in `border` (one flag per input vertex) the vertices shared by two blocks,
/// and gives every block the triangles of its neighbours whose box comes within marginMm of its
/// cell as obstacles. blockMm <= 0: one block with everything, no border. Blocks in cell order.
std::vector<Block> makeBlocks(const State& st, double blockMm, double offsetMm, double marginMm,
                              std::vector<char>& border);

/// One block of the live triangles within two rings of a vertex that is not settled (State::
/// settled), its border in `border`: all that a last pass can still collapse.
std::vector<Block> unsettledBlock(const State& st, std::vector<char>& border);

/// Blocks, blocks shifted by half a block (the first pass's borders inside), by a quarter (the
/// second's inside), then one serial pass over the unsettled block (everything with
/// SimplifyOptions::exhaustiveIntersectionChecks; SimplifyOptions::blockMm 0: that pass only). Updates `st`; reports progress on `stage`
/// up to 0.97. Returns the number of collapses. Throws Cancelled. The result does not depend on
/// the thread count.
std::size_t simplifyInPasses(State& st, const SimplifyOptions& options, Progress& progress, ProgressStage& stage);

}  // namespace jawmesh::simplify
