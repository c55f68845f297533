// File-name checks shared by the readers and writers.
#pragma once

#include <string>

namespace jawmesh {

/// Whether `name` ends with `suffix`, letters compared without case (".NII.GZ" ends with ".nii.gz").
bool endsWithIgnoringCase(const std::string& name, const std::string& suffix);

}  // namespace jawmesh
