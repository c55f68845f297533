// A "lid": a piece of an interface sheet whose whole boundary is open, lying within the hole loop
// that bounds it. Where a repaired level set jumps between tiles (docs/DESIGN.md, Known pitfalls)
// the extraction could keep one face of a small box of a region (a bone blob 0.4 mm off the bone,
// a square inside a tooth's missing tile face) and miss the rest; its rim is then a hole loop, and
// the patch over that loop would lie on the lid itself. Removing the lid closes the loop instead.
#pragma once

#include "filters/HoleLoops.h"
#include "io/VertexTriangles.h"

#include <cstdint>
#include <unordered_set>
#include <vector>

namespace jawmesh {

/// The triangles of the loop's sheet reached from the loop's edges without crossing an edge in
/// `openEdges` (edgeKey of every open edge of the sheet), when all of them lie within the loop's
/// bounding box (widened by a hundredth of its diagonal): a lid bounded by open edges only.
/// Empty when the sheet runs on beyond the loop (an ordinary hole in a larger sheet).
/// `removed` marks triangles already taken out (skipped). Cost: O(size of the lid + its edges).
std::vector<std::int32_t> lidInsideLoop(const InterfaceComplex& complex, const VertexTriangles& vt, const HoleLoop& loop,
                                        const std::unordered_set<std::uint64_t>& openEdges, const std::vector<char>& removed);

}  // namespace jawmesh
