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
    // A direction across the axis from which azimuths are counted.
    const openvdb::Vec3d a = axis.axis;
    const openvdb::Vec3d u = (std::abs(a.x()) < 0.9 ? openvdb::Vec3d(1, 0, 0) : openvdb::Vec3d(0, 1, 0)).cross(a).unit();
    const openvdb::Vec3d v = a.cross(u);
    std::vector<double> top(kCrestBins, -std::numeric_limits<double>::infinity());
    auto B = bone.getConstAccessor();
    for (auto leaf = near.cbeginLeaf(); leaf; ++leaf)
        for (auto it = leaf->cbeginValueOn(); it; ++it) {
            float b;
            if (!B.probeValue(it.getCoord(), b) || std::abs(b) > voxel) continue;
            const openvdb::Vec3d d = xf.indexToWorld(it.getCoord()) - axis.origin;
            const double phi = std::atan2(d.dot(v), d.dot(u)) + M_PI;
            const int bin = std::min(kCrestBins - 1, int(phi / (2 * M_PI) * kCrestBins));
            top[bin] = std::max(top[bin], d.dot(a));
        }
    for (double h : top)
        if (std::isfinite(h)) crest.heightsMm.push_back(h);
    if (crest.heightsMm.empty()) throw Error(what + ": no bone lies within " + std::to_string(kCrestReachMm) + " mm of the tooth");
    std::vector<double> sorted = crest.heightsMm;
    std::sort(sorted.begin(), sorted.end());
    crest.minMm = sorted.front();
    crest.lowMm = sorted[std::size_t(0.1 * double(sorted.size() - 1))];
    double sum = 0;
    for (double h : sorted) sum += h;
    crest.meanMm = sum / double(sorted.size());
    return crest;
}

}  // namespace jawmesh
