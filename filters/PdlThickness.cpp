// Implements filters/PdlThickness.h; what it computes, its rules and its contract are documented there.
#include "filters/PdlThickness.h"

#include "io/Error.h"

namespace jawmesh {

PdlThickness pdlThickness(const SurfaceMesh& toothSide, const SurfaceMesh& boneSide, double spacingMm,
                          double toleranceMm, Progress& progress) {
    if (toothSide.triangles.empty()) throw Error("PDL thickness: the PDL has no interface with its tooth");
    if (boneSide.triangles.empty()) throw Error("PDL thickness: the PDL has no interface with the bone");
    const TriangleBvh bone = buildTriangleBvh(boneSide);
    PdlThickness out;
    out.samples = sampleDistances(toothSide, bone, spacingMm, progress);
    const std::vector<int> oneGroup(toothSide.triangles.size(), 0);
    out.summary = summarizeDistances(toothSide, out.samples, oneGroup, 1, bone, toleranceMm, progress).front();
    return out;
}

}  // namespace jawmesh
