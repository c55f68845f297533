// A healed extraction socket (issue #24): after a tooth is taken out, bone fills its socket up to
// a low point of the crest around it. The fill is the tooth dilated by the widest root-socket gap
// carving bridges (so no film of air is left along the old socket wall), cut by a plane across
// the tooth's long axis at the crest's low height (the 10th percentile of its sectors,
// AlveolarCrest.h), and united with the bone. A plane low on the rim leaves the higher parts
// (between the teeth) as they were, as a healed ridge does; the fill rises above the bone only
// where the rim dips below that height (at most a tenth of it).
#pragma once

#include "levelset/ToothLongAxis.h"

#include <openvdb/openvdb.h>

#include <string>

namespace jawmesh {

struct SocketFill {
    double levelMm = 0;          ///< height of the fill's top along the tooth's axis
    double filledVolumeMm3 = 0;  ///< bone gained (voxels that turned inside)
};

/// The bone with the socket of `tooth` filled (see the file comment); gapMm is the dilation.
/// Throws Error("<what>: ...") when no bone lies around the tooth (no socket to heal).
/// Cost: a closest-point propagation around the tooth, a rewrite of the voxels the fill reaches.
openvdb::FloatGrid::Ptr healSocket(const openvdb::FloatGrid& bone, const openvdb::FloatGrid& tooth, const LongAxis& axis,
                                   double gapMm, SocketFill& fill, const std::string& what);

}  // namespace jawmesh
