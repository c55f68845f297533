// Abaqus / CalculiX input deck (.inp) of a scenario: nodes, C3D4 or C3D10 elements in one element
// set per region, node sets per region and per condition, neo-Hookean materials, one static
// nonlinear step with *BOUNDARY and *CLOAD, and output requests that CalculiX writes to .frd / .dat.
// A contact scenario (biting) adds the exposed crowns of each jaw as element-face surfaces and a
// penalty surface-to-surface *CONTACT PAIR between them.
#pragma once

#include "fe/Materials.h"
#include "fe/Scenario.h"
#include "io/TetMesh.h"

#include <string>

namespace jawmesh {

struct CalculixOptions {
    int order = 1;                 ///< 1: C3D4; 2: C3D10 for the whole mesh (mid-edge nodes shared)
    /// Load fraction of the first increment (step time 1). The full load at once suits the small
    /// tipping loads; ccx cuts the increment back by itself when Newton does not converge.
    double initialIncrement = 1.0;
    int maxIncrements = 100;
    /// Contact scenarios: first increment (contact needs the load ramped) and the slope of the
    /// linear pressure-overclosure law in units of the tooth's Young modulus per mm (CalculiX's
    /// guide: 5 to 50 times the modulus of the adjacent material).
    double contactInitialIncrement = 0.05;
    double contactStiffnessPerModulus = 10.0;
};

/// Set names used in the deck (CalculiX upper-cases them in its output files):
/// element and node set per region = labelName(label) ("bone_mandible", "tooth_24", "pdl_24");
/// FixedSet::name for each Dirichlet set; "loadpt_tooth_<UNN>" = the reference node of each
/// tooth load and "loadpts" = all of them (printed to .dat with *NODE PRINT); contact:
/// "crowns_mandible" (slave) and "crowns_maxilla" (master) surfaces, interaction "occlusal_contact".
/// Node numbers are mesh node index + 1 (mid-edge nodes of C3D10 follow the corner nodes);
/// element numbers are tet index + 1.
std::string calculixLoadPointSet(int unn);
constexpr const char* kCalculixLoadPointsSet = "loadpts";

/// Writes `scenario` on `mesh` as a CalculiX deck at `path` (atomically). Loads become consistent
/// nodal forces (*CLOAD) of the order used. Output: U and S to the .frd (*NODE FILE, *EL FILE);
/// U of the load points and S of every region's elements to the .dat (*NODE PRINT, *EL PRINT),
/// which readCalculixDat() reads back.
/// Throws Error for a contact scenario whose mesh lacks the crowns of either jaw, an order other
/// than 1 or 2, unknown labels, or I/O failure.
/// Cost: O(nodes + tets); about 80 bytes per C3D4 element.
void writeCalculixDeck(const TetMesh& mesh, const FeScenario& scenario, const MaterialTable& materials,
                       const std::string& path, const CalculixOptions& options = {});

}  // namespace jawmesh
