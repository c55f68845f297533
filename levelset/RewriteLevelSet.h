// Local rewrites of a level set, the step under every edit of the jaw (levelset/JawEdits.h): new
// values on some voxels, then the inside / outside of everything else re-decided from the band, so
// that what the new values enclose becomes inside (a healed socket) and what they cut off becomes
// outside (a lowered crest) without visiting the volume in between.
#pragma once

#include <openvdb/openvdb.h>

#include <functional>

namespace jawmesh {

/// A copy of `grid` (a level set, mm) holding value(ijk) on every voxel of `where` (active when
/// within the band, else the background with its sign), every other active voxel as it was, and
/// every inactive voxel and tile re-signed from the active ones (openvdb::tools::signedFloodFill,
/// after inactive leaves become tiles).
/// The new values must form, with the untouched band around `where`, a band around the new surface
/// at least two voxels wide on each side. `value` is called concurrently (read grids through their
/// trees, not shared accessors). Throws Error for a grid that is not a level set.
/// Cost: |where| calls in parallel, a serial merge, one flood fill over the grid.
openvdb::FloatGrid::Ptr rewriteLevelSet(const openvdb::FloatGrid& grid, const openvdb::MaskTree& where,
                                        const std::function<float(const openvdb::Coord&)>& value);

}  // namespace jawmesh
