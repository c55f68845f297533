// The alveolar crest around a tooth, measured on the level sets: the bone's surface voxels within
// reach of the tooth's surface, binned by azimuth around the tooth's long axis; in each bin the
// highest of them is the crest there. Edits use it to place a healed socket's top and the cut of
// a bone loss (levelset/JawEdits.h), and record it before and after.
#pragma once

#include "levelset/ToothLongAxis.h"

#include <openvdb/openvdb.h>

#include <vector>

namespace jawmesh {

struct CrestProfile {
    std::vector<double> heightsMm;  ///< per azimuth bin with bone: the crest's height along the axis
    std::vector<double> sectorHeightsMm;  ///< the same for every bin (LongAxis::sectorOf), NaN without bone
    double minMm = 0;               ///< the lowest bin
    double lowMm = 0;               ///< a low crest height: the 10th percentile of the bins
    double meanMm = 0;              ///< mean of the bins
    double apexMm = 0;              ///< lowest height of the tooth's surface (its apex)
    /// Per sector (kCrestBins), the tooth's distance from its axis within kCrestRadiusBandMm of
    /// the crest's mean height: how far the root reaches at the crest in that direction, mm.
    std::vector<double> rootRadiusMm;
};

/// Azimuth bins of crestAround (10 degrees each).
constexpr int kCrestBins = 36;
/// How far from the tooth's surface a bone surface voxel still belongs to its socket rim, mm.
constexpr double kCrestReachMm = 0.6;
/// The root's radius at the crest is taken over this far above and below the crest's mean, mm.
constexpr double kCrestRadiusBandMm = 1.0;

/// The crest of the bone around `tooth` along `axis` (see the file comment); grids on one
/// transform. Throws Error("<what>: ...") when no bone surface lies within kCrestReachMm of the
/// tooth (a tooth without a socket has no crest).
CrestProfile crestAround(const openvdb::FloatGrid& bone, const openvdb::FloatGrid& tooth, const LongAxis& axis,
                         const std::string& what);

}  // namespace jawmesh
