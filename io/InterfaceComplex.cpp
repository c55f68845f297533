// Implements io/InterfaceComplex.h; what it computes, its rules and its contract are documented there.
#include "io/InterfaceComplex.h"

#include <algorithm>

namespace jawmesh {

int interfaceMarker(Label a, Label b) { return 1024 * std::min(a, b) + std::max(a, b); }

std::array<Label, 2> interfacePairFromMarker(int marker) { return {marker / 1024, marker % 1024}; }

}  // namespace jawmesh

namespace jawmesh {

InterfaceComplex withoutCarried(InterfaceComplex complex) {
    if (!complex.carried.empty()) {
        // Corners come first: the carried vertices are the tail past the largest corner index.
        std::int32_t corners = 0;
        for (const Tri& t : complex.surface.triangles)
            for (std::int32_t v : t) corners = std::max(corners, v + 1);
        complex.surface.vertices.resize(std::size_t(corners));
    }
    complex.carried.clear();
    complex.sampleErrorMm.clear();
    return complex;
}

}  // namespace jawmesh
