// Implements levelset/JawInput.h; what it computes, its rules and its contract are documented there.
#include "levelset/JawInput.h"

#include "io/Error.h"
#include "io/LabelRoles.h"
#include "io/LabelVolume.h"
#include "io/ToothAxes.h"
#include "levelset/LabelVolumeSurfaces.h"

#include <array>
#include <cmath>
#include <sstream>
#include <utility>

namespace jawmesh {

JawSurfaces loadJawInput(const JawCase& jc, const LoadOptions& options, Progress& progress) {
    if (jc.labelVolumePath.empty()) return loadJaw(jc, options, progress);
    requireValidScale(options, jc.labelVolumePath);
    LabelVolume volume = [&] {
        ProgressStage stage(progress, "read " + jawName(jc.jaw) + " label volume");
        return readLabelVolume(jc.labelVolumePath);
    }();
    if (options.scale > 0) volume.directionsMm *= options.scale, volume.originMm *= options.scale;
    const LabelAssignment roles = assignLabelRoles(volume, jc.jaw, jc.labelsJsonPath);
    const std::array<int, 3> size = volume.size;
    const Eigen::Matrix3d directions = volume.directionsMm;
    JawSurfaces out = surfacesFromLabelVolume(std::move(volume), roles, jc.jaw, progress);
    if (!jc.axesPath.empty()) out.axes = readToothAxes(jc.axesPath);
    std::ostringstream note;
    note << "read from the label volume " << jc.labelVolumePath << ": " << size[0] << " x " << size[1] << " x " << size[2]
         << " voxels of " << directions.col(0).norm() << " x " << directions.col(1).norm() << " x " << directions.col(2).norm()
         << " mm, " << out.teeth.size() << " teeth";
    out.notes.push_back(note.str());
    return out;
}

}  // namespace jawmesh
