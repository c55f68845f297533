// Implements levelset/JawInput.h; what it computes, its rules and its contract are documented there.
#include "levelset/JawInput.h"

#include "io/Error.h"
#include "io/LabelRoles.h"
#include "io/LabelVolume.h"
#include "io/ToothAxes.h"
#include "levelset/LabelVolumeSurfaces.h"

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
    std::ostringstream note;
    note << "read from the label volume " << jc.labelVolumePath << ": " << volume.size[0] << " x " << volume.size[1] << " x "
         << volume.size[2] << " voxels of " << volume.directionsMm.col(0).norm() << " x " << volume.directionsMm.col(1).norm()
         << " x " << volume.directionsMm.col(2).norm() << " mm, ";
    JawSurfaces out = surfacesFromLabelVolume(std::move(volume), roles, jc.jaw, progress);
    if (!jc.axesPath.empty()) out.axes = readToothAxes(jc.axesPath);
    note << out.teeth.size() << " teeth";
    out.notes.push_back(note.str());
    return out;
}

}  // namespace jawmesh
