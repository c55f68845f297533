// Figures of a finished `jawmesh run` jaw folder, computed here independently of the pipeline's
// own report: what issue #5 asks of every run (conformity, quality, size, PDL thickness, distance
// of every output region to its input surface).
#pragma once

#include "io/SurfaceMesh.h"
#include "io/TetMesh.h"
#include "tet/ElementQuality.h"
#include "tet/ValidateTetMesh.h"

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace jawmesh::test {

/// Exact distance from points to a triangle surface, accelerated by a uniform grid of triangle
/// boxes (rings searched outward until no nearer triangle can exist).
class SurfaceDistance {
public:
    SurfaceDistance(const SurfaceMesh& surface, double cellMm);
    double operator()(const Vec3& p) const;

private:
    const SurfaceMesh& s_;
    double h_;
    Vec3 origin_;
    int n_[3];
    std::vector<std::vector<std::int32_t>> cells_;
};

/// Largest distance of the vertices and triangle centroids of `from` to `to`, leaving out the points
/// for which `skip` is true (none by default; called from several threads).
double directedHausdorff(const SurfaceMesh& from, const SurfaceDistance& to,
                         const std::function<bool(const Vec3&)>& skip = nullptr);

/// Two-sided Hausdorff distance (mm) of the output bone of <jawDir>/volumetric_meshes/<jaw>.msh to
/// the input bone <inputJawDir>/bone/<jaw>.stl over the points outside every ball (centre, radius
/// mm) of `away`: the bone where the input had no holes.
double boneHausdorffAwayFrom(const std::string& jawDir, const std::string& inputJawDir, const std::string& jaw,
                             const std::vector<std::pair<Vec3, double>>& away);

struct RunFigures {
    ValidationReport validation;
    QualityStats quality;
    std::map<int, double> pdlThicknessMeanMm;  ///< per UNN: area-weighted mean over the tooth-side interface
    std::map<int, double> toothHausdorffMm;    ///< per UNN: two-sided, output tooth surface vs input
    double boneHausdorffMm = 0;                ///< two-sided, output bone surface vs input
};

/// Reads <jawDir>/volumetric_meshes/<jaw>.msh and the input surfaces in <inputJawDir>
/// (bone/<jaw>.stl, teeth/tooth_<UNN>.stl) and measures everything above.
RunFigures measureRun(const std::string& jawDir, const std::string& inputJawDir, const std::string& jaw,
                      const std::vector<int>& teethUnn);

/// Volume (mm^3) of the tets with a label in `labels` below the plane through `origin` with unit
/// normal `up` (the part where (x - origin) . up < 0), each tet clipped exactly by the plane.
double volumeBelowPlaneMm3(const TetMesh& mesh, const std::vector<Label>& labels, const Vec3& origin, const Vec3& up);

/// The alveolar crest around a tooth on a mesh, as levelset/AlveolarCrest.h defines it on grids:
/// the bone's surface vertices within reachMm of the tooth's surface, binned by azimuth (36 bins)
/// around the axis (origin, unit up); per bin the highest (height along up, mm). Bins without bone
/// are left out.
std::vector<double> crestHeightsMm(const TetMesh& mesh, Label bone, int unn, const Vec3& origin, const Vec3& up,
                                   double reachMm = 0.6);

/// The UNNs of the tooth_<UNN>.* files in a case's teeth folder, sorted.
std::vector<int> teethIn(const std::string& teethDir);

/// Prints the figures and asserts (gtest EXPECTs) what every mesh must be, whatever its PDL: valid
/// and conformal (no defect of any kind, every tooth and PDL present), minimum dihedral >= 10
/// degrees with no tet under it.
void expectSoundMesh(const RunFigures& f, const std::vector<int>& teeth);

/// expectSoundMesh and what issue #5 asks of every run: at most maxTets tets (#5's 800 k), PDL mean
/// 0.200 +- 0.01 mm and tooth Hausdorff <= toothBoundMm per tooth (#5's 0.15 mm), bone Hausdorff <=
/// boneBoundMm (#5's 0.25 mm).
void expectRunMeetsTargets(const RunFigures& f, const std::vector<int>& teeth, double boneBoundMm = 0.25,
                           double toothBoundMm = 0.15, std::size_t maxTets = 800000);

}  // namespace jawmesh::test
