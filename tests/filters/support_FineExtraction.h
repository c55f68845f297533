// The fine extraction (one vertex per dual cell, no merged blocks): the reference the adaptive
// extraction and the simplifier are measured against in the filters' tests.
#pragma once

#include "filters/ExtractInterfaces.h"

namespace jawmesh::test {

inline ExtractOptions fineExtraction() {
    ExtractOptions e;
    e.adaptive.maxLevel = 0;
    return e;
}

}  // namespace jawmesh::test
