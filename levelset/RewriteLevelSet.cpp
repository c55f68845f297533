// Implements levelset/RewriteLevelSet.h; what it computes, its rules and its contract are documented there.
#include "levelset/RewriteLevelSet.h"

#include "levelset/Csg.h"

#include <openvdb/tools/Prune.h>
#include <openvdb/tree/LeafManager.h>

#include <tbb/parallel_for.h>

#include <cmath>

namespace jawmesh {

openvdb::FloatGrid::Ptr rewriteLevelSet(const openvdb::FloatGrid& grid, openvdb::MaskTree where,
                                        const std::function<VoxelValue()>& makeValue) {
    const float bg = float(bandHalfWidthMm(grid));
    where.voxelizeActiveTiles();
    openvdb::FloatTree values(where, bg, openvdb::TopologyCopy());
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(values);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.leafCount()), [&](const auto& r) {
        const VoxelValue value = makeValue();
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            for (auto v = leaves.leaf(i).beginValueOn(); v; ++v) v.setValue(value(v.getCoord()));
    });
    auto out = grid.deepCopy();
    auto acc = out->getAccessor();
    for (auto v = values.cbeginValueOn(); v; ++v) {
        const float x = *v;
        float old;
        const bool wasOn = acc.probeValue(v.getCoord(), old);
        if (std::abs(x) < bg) {
            if (!wasOn || old != x) acc.setValue(v.getCoord(), x);
        } else if (wasOn || (old < 0) != (x < 0)) {
            acc.setValueOff(v.getCoord(), x < 0 ? -bg : bg);
        }
    }
    openvdb::tools::pruneLevelSet(out->tree());
    return out;
}

}  // namespace jawmesh
