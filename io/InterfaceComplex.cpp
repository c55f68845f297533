#include "io/InterfaceComplex.h"

#include <algorithm>

namespace jawmesh {

int interfaceMarker(Label a, Label b) { return 1024 * std::min(a, b) + std::max(a, b); }

std::array<Label, 2> interfacePairFromMarker(int marker) { return {marker / 1024, marker % 1024}; }

}  // namespace jawmesh
