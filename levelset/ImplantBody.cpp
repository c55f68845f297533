// Implements levelset/ImplantBody.h; what it computes, its rules and its contract are documented there.
#include "levelset/ImplantBody.h"

#include "levelset/Csg.h"

#include <openvdb/tools/SignedFloodFill.h>

#include <algorithm>
#include <cmath>

namespace jawmesh {
namespace {

/// How far the abutment reaches into the crown above the crest, mm: the two overlap, so the crown
/// sits on the abutment without a seam.
constexpr double kAbutmentIntoCrownMm = 1.0;
/// The abutment stands this far clear of the crest before the crown flares out of it at 45 degrees
/// (its emergence profile), mm. A crown cut flat at the crest lay on the healed bone's flat top:
/// the outside between the two was a wedge as thin as the bone's slope, and TetGen left 5 bone tets
/// under 10 degrees there (shared mandible, implant 19).
constexpr double kCollarMm = 0.5;

/// Largest slope of a screw's radius profile (dr / d depth): pi * thread depth / pitch.
double threadSlope(const ImplantEdit& e) {
    return e.body == ImplantEdit::Body::Screw ? M_PI * e.threadDepthMm / e.threadPitchMm : 0.0;
}

/// Signed distance (mm) of a point at height h on the axis (from the platform, up positive) and
/// lateral distance rho from it to the body and abutment: a capped cylinder from -length to top
/// whose radius below the platform is the body's profile.
double bodyDistance(const ImplantEdit& e, double h, double rho, double topMm) {
    const double radius = h < 0 ? implantRadiusMm(e, std::min(-h, e.lengthMm)) : 0.5 * e.diameterMm;
    const double slope = h < 0 ? threadSlope(e) : 0.0;
    const double dx = (rho - radius) / std::sqrt(1.0 + slope * slope);
    const double dy = std::max(-e.lengthMm - h, h - topMm);
    return std::min(std::max(dx, dy), 0.0) + std::hypot(std::max(dx, 0.0), std::max(dy, 0.0));
}

/// Index box of the body and abutment with a margin of `marginMm` (the axis-aligned box of the
/// segment's end discs).
openvdb::CoordBBox bodyBox(const ImplantEdit& e, const ImplantPlacement& at, double topMm, double marginMm,
                           const openvdb::math::Transform& xf) {
    const openvdb::Vec3d a = at.axis.origin + at.axis.axis * (at.platformMm - e.lengthMm);
    const openvdb::Vec3d b = at.axis.origin + at.axis.axis * (at.platformMm + topMm);
    const double r = 0.5 * e.diameterMm + marginMm;
    openvdb::CoordBBox box;
    for (const openvdb::Vec3d& end : {a, b})
        for (int corner = 0; corner < 8; ++corner) {
            const openvdb::Vec3d p = end + openvdb::Vec3d(corner & 1 ? r : -r, corner & 2 ? r : -r, corner & 4 ? r : -r);
            box.expand(openvdb::Coord::floor(xf.worldToIndex(p)));
            box.expand(openvdb::Coord::floor(xf.worldToIndex(p)) + openvdb::Coord(1));
        }
    return box;
}

}  // namespace

double implantRadiusMm(const ImplantEdit& e, double depthMm) {
    const double outer = 0.5 * e.diameterMm;
    if (e.body != ImplantEdit::Body::Screw) return outer;
    return outer - e.threadDepthMm * 0.5 * (1.0 - std::cos(2.0 * M_PI * depthMm / e.threadPitchMm));
}

double implantBodyVolumeMm3(const ImplantEdit& e) {
    if (e.body != ImplantEdit::Body::Screw) return M_PI * 0.25 * e.diameterMm * e.diameterMm * e.lengthMm;
    // Simpson's rule over 64 steps a thread: the profile is a raised cosine, exact to 1e-9 relative.
    const int steps = 2 * int(std::ceil(32.0 * e.lengthMm / e.threadPitchMm));
    const double dz = e.lengthMm / steps;
    double sum = 0;
    for (int i = 0; i <= steps; ++i) {
        const double r = implantRadiusMm(e, i * dz);
        sum += (i == 0 || i == steps ? 1 : (i % 2 ? 4 : 2)) * M_PI * r * r;
    }
    return sum * dz / 3.0;
}

openvdb::FloatGrid::Ptr implantLevelSet(const ImplantEdit& e, const ImplantPlacement& at, const openvdb::FloatGrid& tooth) {
    const double bg = bandHalfWidthMm(tooth);
    const double voxel = uniformVoxelSizeMm(tooth);
    const auto& xf = tooth.transform();
    // Heights from the platform; with a crown the abutment reaches into it, else the body ends flat.
    const double crestAbove = at.crestMm - at.platformMm;
    const double collarTop = crestAbove + kCollarMm;
    const double topMm = e.crown ? collarTop + kAbutmentIntoCrownMm : 0.0;
    openvdb::CoordBBox box = bodyBox(e, at, topMm, bg + voxel, xf);
    if (e.crown) box.expand(tooth.evalActiveVoxelBoundingBox());

    auto grid = openvdb::FloatGrid::create(float(bg));
    grid->setTransform(xf.copy());
    auto out = grid->getAccessor();
    auto T = tooth.getConstAccessor();
    for (auto it = box.begin(); it; ++it) {
        const openvdb::Vec3d p = xf.indexToWorld(*it);
        const double h = at.axis.heightOf(p) - at.platformMm, rho = at.axis.lateralOf(p);
        double d = bodyDistance(e, h, rho, topMm);
        // The crown: the tooth above a cone rising at 45 degrees from the collar's rim.
        if (e.crown)
            d = std::min(d, std::max(double(T.getValue(*it)), (collarTop + rho - 0.5 * e.diameterMm - h) * M_SQRT1_2));
        if (std::abs(d) < bg) out.setValue(*it, float(d));
    }
    openvdb::tools::signedFloodFill(grid->tree());
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    if (threadSlope(e) > 0) grid = renormalizeLevelSet(*grid, bg / voxel, bg / voxel);
    grid->setName("implant");
    return grid;
}

}  // namespace jawmesh
