// Implements levelset/ToothLongAxis.h; what it computes, its rules and its contract are documented there.
#include "levelset/ToothLongAxis.h"

#include "levelset/Csg.h"

#include <Eigen/Eigenvalues>

namespace jawmesh {

LongAxis toothLongAxis(const std::vector<openvdb::Vec3d>& surface, const std::vector<char>& contact,
                       const ToothAxes* given) {
    LongAxis a;
    if (given) {
        a.origin = openvdb::Vec3d(given->crownCentre.x(), given->crownCentre.y(), given->crownCentre.z());
        a.axis = openvdb::Vec3d(given->occlusal.x(), given->occlusal.y(), given->occlusal.z()).unit();
        return a;
    }
    if (surface.empty()) return a;
    openvdb::Vec3d mean(0, 0, 0);
    for (const auto& p : surface) mean += p;
    mean /= double(surface.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : surface) {
        const Eigen::Vector3d d(p[0] - mean[0], p[1] - mean[1], p[2] - mean[2]);
        cov += d * d.transpose();
    }
    const Eigen::Vector3d v = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(2);
    a.origin = mean;
    a.axis = openvdb::Vec3d(v.x(), v.y(), v.z());
    // Orient towards the crown: the root (bone contact) lies on the negative side.
    double hc = 0;
    std::size_t nc = 0;
    for (std::size_t i = 0; i < surface.size(); ++i)
        if (contact[i]) hc += a.heightOf(surface[i]), ++nc;
    if (nc && hc / double(nc) > 0) a.axis = -a.axis;
    return a;
}

LongAxis toothLongAxis(const openvdb::FloatGrid& tooth, const openvdb::FloatGrid& bone, double contactMm,
                       const ToothAxes* given) {
    const double voxel = uniformVoxelSizeMm(tooth);
    std::vector<openvdb::Vec3d> surface;
    std::vector<char> contact;
    auto B = bone.getConstAccessor();
    for (auto it = tooth.tree().cbeginValueOn(); it; ++it) {
        if (*it >= 0 || *it < -2 * voxel) continue;
        surface.push_back(tooth.transform().indexToWorld(it.getCoord()));
        // Off the bone's band the value is its background, which may be under contactMm: only band
        // values and the inside count.
        float b;
        const bool band = B.probeValue(it.getCoord(), b);
        contact.push_back(band ? b < contactMm : b < 0);
    }
    return toothLongAxis(surface, contact, given);
}

}  // namespace jawmesh
