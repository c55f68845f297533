// The surfaces of a jaw case, whatever its input: surface files (io/Case.h loadJaw) or a label
// volume (levelset/LabelVolumeSurfaces.h). Every command that takes a case reads it through here.
#pragma once

#include "io/Case.h"

namespace jawmesh {

/// loadJaw for surface input; for a label volume: the volume, its roles (labels.json or segment
/// names), the surfaces, and the axes file when present. LoadOptions::scale multiplies the label
/// volume's coordinates too. Throws Error naming the file, Cancelled when progress is cancelled.
JawSurfaces loadJawInput(const JawCase& jawCase, const LoadOptions& options = {}, Progress& progress = noProgress());

}  // namespace jawmesh
