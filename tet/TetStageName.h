// The name the tet stage's errors carry ("tetrahedralize: ..."), one for all of its files.
#pragma once

namespace jawmesh {

inline constexpr const char* kTetStageName = "tetrahedralize";

}  // namespace jawmesh
