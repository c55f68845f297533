// Implements levelset/RewriteLevelSet.h; what it computes, its rules and its contract are documented there.
#include "levelset/RewriteLevelSet.h"

#include "levelset/Csg.h"

#include <openvdb/tools/Prune.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tree/LeafManager.h>

#include <tbb/parallel_for.h>

#include <cmath>

namespace jawmesh {

openvdb::FloatGrid::Ptr rewriteLevelSet(const openvdb::FloatGrid& grid, const openvdb::MaskTree& where,
                                        const std::function<float(const openvdb::Coord&)>& value) {
    const float bg = float(bandHalfWidthMm(grid));
    openvdb::FloatTree values(where, bg, openvdb::TopologyCopy());
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(values);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.leafCount()), [&](const auto& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            for (auto v = leaves.leaf(i).beginValueOn(); v; ++v) v.setValue(value(v.getCoord()));
    });
    auto out = grid.deepCopy();
    auto acc = out->getAccessor();
    for (auto v = values.cbeginValueOn(); v; ++v) {
        const float x = *v;
        if (std::abs(x) < bg) acc.setValue(v.getCoord(), x);
        else acc.setValueOff(v.getCoord(), x < 0 ? -bg : bg);
    }
    // signedFloodFill keeps the sign of a leaf with no active voxel (it re-signs tiles only): such
    // leaves become tiles first, so a cut-off region deep inside the old surface turns outside.
    openvdb::tools::pruneInactive(out->tree());
    openvdb::tools::signedFloodFill(out->tree());
    return out;
}

}  // namespace jawmesh
