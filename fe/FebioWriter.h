// FEBio input file (febio_spec 4.0, readable by FEBio Studio) of a scenario: nodes, one element
// block and solid domain per region label, neo-Hookean materials per region kind, node sets for
// the fixed conditions, load patches as surfaces with traction loads under a load controller, and
// for contact scenarios the crowns of the two jaws as a sliding contact pair.
#pragma once

#include "fe/Materials.h"
#include "fe/Scenario.h"
#include "io/TetMesh.h"

#include <string>

namespace jawmesh {

struct FebioOptions {
    int order = 1;          ///< 1: tet4 everywhere; 2: tet10 everywhere (mid-edge nodes shared, tri6 surfaces)
    int timeSteps = 10;     ///< load ramped linearly over time 0..1
};

/// Writes `scenario` on `mesh` to `path` (atomically). Node ids are node index + 1 (mid-edge nodes
/// of tet10 follow); element ids run 1..T block by block in label order; the MeshDomains follow the
/// element blocks in the same order, as FEBio requires. Set and surface names: FixedSet::name,
/// SurfaceLoad::name, "crowns_maxilla" / "crowns_mandible" for contact.
/// Throws Error for an order other than 1 or 2, unknown labels, or I/O failure. Cost: O(nodes + tets).
void writeFebioDeck(const TetMesh& mesh, const FeScenario& scenario, const MaterialTable& materials,
                    const std::string& path, const FebioOptions& options = {});

}  // namespace jawmesh
