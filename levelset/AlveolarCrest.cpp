// Implements levelset/AlveolarCrest.h; what it computes, its rules and its contract are documented there.
#include "levelset/AlveolarCrest.h"

#include "io/Error.h"
#include "levelset/Csg.h"

#include <openvdb/tools/Morphology.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace jawmesh {

CrestProfile crestAround(const openvdb::FloatGrid& bone, const openvdb::FloatGrid& tooth, const LongAxis& axis,
                         const std::string& what) {
    requireSameTransform(bone, tooth, "crest");
    const double voxel = uniformVoxelSizeMm(bone);
    const auto& xf = bone.transform();
    CrestProfile crest;
    crest.apexMm = std::numeric_limits<double>::infinity();
    for (auto it = tooth.tree().cbeginValueOn(); it; ++it)
        if (*it <= 0) crest.apexMm = std::min(crest.apexMm, axis.heightOf(xf.indexToWorld(it.getCoord())));
    // Voxels within reach of the tooth: its band, dilated (Chebyshev: a little farther on diagonals).
    openvdb::MaskTree near(tooth.tree(), false, openvdb::TopologyCopy());
    const int reach = std::max(1, int(std::ceil((kCrestReachMm - bandHalfWidthMm(tooth)) / voxel)));
    openvdb::tools::dilateActiveValues(near, reach, openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::IGNORE_TILES);
    std::vector<double> top(kCrestBins, -std::numeric_limits<double>::infinity());
    auto B = bone.getConstAccessor();
    for (auto leaf = near.cbeginLeaf(); leaf; ++leaf)
        for (auto it = leaf->cbeginValueOn(); it; ++it) {
            float b;
            if (!B.probeValue(it.getCoord(), b) || std::abs(b) > voxel) continue;
            const openvdb::Vec3d p = xf.indexToWorld(it.getCoord());
            const int bin = axis.sectorOf(p, kCrestBins);
            top[bin] = std::max(top[bin], axis.heightOf(p));
        }
    for (double h : top) {
        crest.sectorHeightsMm.push_back(std::isfinite(h) ? h : std::numeric_limits<double>::quiet_NaN());
        if (std::isfinite(h)) crest.heightsMm.push_back(h);
    }
    if (crest.heightsMm.empty()) throw Error(what + ": no bone lies within " + std::to_string(kCrestReachMm) + " mm of the tooth");
    std::vector<double> sorted = crest.heightsMm;
    std::sort(sorted.begin(), sorted.end());
    crest.minMm = sorted.front();
    crest.lowMm = sorted[std::size_t(0.1 * double(sorted.size() - 1))];
    double sum = 0;
    for (double h : sorted) sum += h;
    crest.meanMm = sum / double(sorted.size());
    crest.rootRadiusMm.assign(kCrestBins, 0.0);
    for (auto it = tooth.tree().cbeginValueOn(); it; ++it) {
        if (*it > 0 || *it < -2 * voxel) continue;
        const openvdb::Vec3d p = xf.indexToWorld(it.getCoord());
        if (std::abs(axis.heightOf(p) - crest.meanMm) > kCrestRadiusBandMm) continue;
        double& r = crest.rootRadiusMm[std::size_t(axis.sectorOf(p, kCrestBins))];
        r = std::max(r, axis.lateralOf(p));
    }
    double widest = 0;
    for (double r : crest.rootRadiusMm) widest = std::max(widest, r);
    for (double& r : crest.rootRadiusMm)
        if (r == 0) r = widest;  // a sector the surface missed: the root's widest reach
    return crest;
}

}  // namespace jawmesh
