// Shape measures of linear tetrahedra: dihedral angles, radius-edge, radius and volume-edge ratios,
// per element and summarised over a mesh (overall and per label).
#pragma once

#include "io/TetMesh.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <vector>

namespace jawmesh {

/// Shape of one tet.
struct TetShape {
    double minDihedralDeg = 0;   ///< smallest of the 6 interior dihedral angles, degrees
    double maxDihedralDeg = 0;   ///< largest, degrees
    double radiusEdgeRatio = 0;  ///< circumradius / shortest edge (regular tet: 0.612, TetGen's -q
                                 ///< measure, kept unnormalised by that convention); inf if flat
    double radiusRatio = 0;      ///< 3 * inradius / circumradius: 1 regular, 0 flat
    double volumeEdgeRatio = 0;  ///< 6 sqrt(2) |V| / (rms edge)^3: 1 regular, 0 flat
    double signedVolume = 0;     ///< mm^3, positive for the orientation of io/TetMesh.h
};

/// Radius-edge ratio of the regular tetrahedron, sqrt(6) / 4 (the lower bound of the measure).
constexpr double kRegularRadiusEdgeRatio = 0.6123724356957945;

/// Shape of the tet (a, b, c, d), mm. Never throws; a flat tet gets dihedrals of 0/180 and an
/// infinite radius-edge ratio. Cost: O(1).
TetShape tetShape(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Shape of every tet of `mesh` (indices must be in range), in tet order. Cost: O(T), TBB-parallel.
std::vector<TetShape> tetShapes(const TetMesh& mesh);

/// Six times the signed volume of tet abcd (positive when d sees abc counter-clockwise), mm^3:
/// the sign tests and volume sums of the sliver improver, without the division.
inline double signedVolume6(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return (b - a).dot((c - a).cross(d - a)); }

/// Signed volume of the tet (a, b, c, d), mm^3: positive for the orientation of io/TetMesh.h.
inline double signedTetVolume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return signedVolume6(a, b, c, d) / 6.0; }

/// Volume of each label's tets, mm^3 (signed volumes summed in tet order, so the same mesh gives
/// the same figures). Cost: O(T).
std::map<Label, double> labelVolumesMm3(const TetMesh& mesh);

/// Quality summary over a mesh.
struct QualityStats {
    std::size_t tets = 0;
    double minDihedralDeg = 180;  ///< over all tets
    double maxDihedralDeg = 0;
    double maxRadiusEdge = 0;
    double meanRadiusEdge = 0;
    std::int64_t worstTet = -1;             ///< tet with the smallest dihedral angle
    std::size_t belowDihedralThreshold = 0; ///< tets whose min dihedral < the threshold given
    std::map<Label, double> minDihedralByLabel;
    std::map<Label, double> maxRadiusEdgeByLabel;
};

/// Measures every tet of `mesh` (indices must be in range). `dihedralThresholdDeg` sets what
/// belowDihedralThreshold counts. Cost: O(T), TBB-parallel; result independent of thread count
/// (ties for worstTet go to the lowest index; the mean is summed in a fixed order).
QualityStats measureQuality(const TetMesh& mesh, double dihedralThresholdDeg = 10.0);

/// As run.json's "quality" records it: min_dihedral_deg, max_dihedral_deg, max_radius_edge and
/// tets_below_min_dihedral (the threshold measureQuality was given).
nlohmann::json toJson(const QualityStats& stats);

}  // namespace jawmesh
