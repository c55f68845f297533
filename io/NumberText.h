// Numbers as text for the writers (meshes, FE decks): std::to_chars, which needs no locale and
// no stream state and is several times faster than an ostream's (printf's) conversion; the
// decks' hundreds of thousands of node coordinates were a serial second of a run.
#pragma once

#include <ostream>
#include <string>

namespace jawmesh {

/// v as text: the shortest that reads back as exactly v (significantDigits 0), else as printf's
/// "%.<significantDigits>g" (the same text an ostream with that precision writes).
std::string numberText(double v, int significantDigits = 0);

/// Writes numberText(v, significantDigits) to `out`.
void writeNumber(std::ostream& out, double v, int significantDigits = 0);

}  // namespace jawmesh
