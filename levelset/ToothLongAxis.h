// A tooth's long axis from its level set: the principal axis of its surface voxels, oriented from
// the root (where the bone is) to the crown, or the case's axes when it has them. Carving uses it
// for the PDL profile and the apex taper; edits (levelset/JawEdits.h) lower a crest and fill a
// socket along it.
#pragma once

#include "io/ToothAxes.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace jawmesh {

struct LongAxis {
    openvdb::Vec3d origin{0, 0, 0};  ///< a point on the axis (the case's crown centre, else the surface's mean), mm
    openvdb::Vec3d axis{0, 0, 1};    ///< unit, from the root toward the crown
    /// Height of a world point along the axis (mm; the crown is up).
    double heightOf(const openvdb::Vec3d& world) const { return (world - origin).dot(axis); }
    /// Distance of a world point from the axis line (mm).
    double lateralOf(const openvdb::Vec3d& world) const {
        const openvdb::Vec3d d = world - origin;
        return (d - axis * d.dot(axis)).length();
    }
    /// A fixed unit direction across the axis (azimuth 0's reference).
    openvdb::Vec3d across() const {
        return (std::abs(axis.x()) < 0.9 ? openvdb::Vec3d(1, 0, 0) : openvdb::Vec3d(0, 1, 0)).cross(axis).unit();
    }
    /// Angle of a world point around the axis, in [0, 2 pi), from a fixed direction across it.
    double azimuthOf(const openvdb::Vec3d& world) const {
        const openvdb::Vec3d u = across();
        const openvdb::Vec3d d = world - origin;
        return std::atan2(d.dot(axis.cross(u)), d.dot(u)) + M_PI;
    }
    /// Which of `bins` equal sectors around the axis a world point lies in.
    int sectorOf(const openvdb::Vec3d& world, int bins) const {
        return std::min(bins - 1, int(azimuthOf(world) / (2 * M_PI) * bins));
    }
};

/// The axis through `surface` (world points on the tooth's surface, mm): `given`'s occlusal axis
/// through its crown centre when given, else the principal axis of the points through their mean,
/// turned so that the points in bone contact (`contact`, one flag per point) lie below the mean.
/// Throws nothing; an empty `surface` gives the default axis.
LongAxis toothLongAxis(const std::vector<openvdb::Vec3d>& surface, const std::vector<char>& contact,
                       const ToothAxes* given);

/// The same from the tooth's level set: its voxels within two voxels inside the surface, in bone
/// contact where the bone's band is under contactMm there, or where they are inside the bone.
LongAxis toothLongAxis(const openvdb::FloatGrid& tooth, const openvdb::FloatGrid& bone, double contactMm,
                       const ToothAxes* given);

}  // namespace jawmesh
