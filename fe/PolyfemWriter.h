// PolyFEM input (its current JSON schema, docs/DESIGN.md pitfalls) of a scenario, with the files it
// references: the mesh as Gmsh 4.1 (.msh), one body id per element (= region label) and the
// boundary faces of every condition with their selection id.
#pragma once

#include "fe/Materials.h"
#include "fe/Scenario.h"
#include "io/TetMesh.h"

#include <string>
#include <vector>

namespace jawmesh {

struct PolyfemOptions {
    bool quadraticPdl = true;   ///< discr_order 2 on PDL bodies (PolyFEM mixes orders conformally)
    double contactDhatMm = 1e-3;  ///< barrier distance when the scenario asks for contact
};

/// Writes `jsonPath` and, beside it, <stem>.msh (tets sorted by label, nodes compacted so that
/// PolyFEM's vertex i is the i-th node written), <stem>_bodies.txt (one label per element, the
/// volume_selection) and <stem>_surfaces.txt (rows "id v0 v1 v2", 0-based vertices, the
/// surface_selection). Selection ids: 1.. for FixedSet (dirichlet_boundary, with "dimension" when
/// not every dof is held), then loads (neumann_boundary with the traction in MPa); a load on
/// exactly the faces of a fixed set shares its id. Materials by body id (= label), NeoHookean.
/// Every file is written atomically. Returns the paths written (JSON last).
/// Throws Error for unknown labels or I/O failure. Cost: O(nodes + tets).
std::vector<std::string> writePolyfemDeck(const TetMesh& mesh, const FeScenario& scenario, const MaterialTable& materials,
                                          const std::string& jsonPath, const PolyfemOptions& options = {});

}  // namespace jawmesh
