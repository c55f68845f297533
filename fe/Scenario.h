// FE scenarios on a labeled tet mesh (docs/DESIGN.md, "FE scenarios"): which nodes are fixed, where
// loads act and how large they are. Plain data that every deck writer turns into its own syntax.
#pragma once

#include "io/ToothAxes.h"
#include "io/TetMesh.h"

#include <array>
#include <map>
#include <string>
#include <vector>

namespace jawmesh {

/// Nodes held by a Dirichlet condition on the dofs marked true (x, y, z in the mesh frame).
struct FixedSet {
    std::string name;                       ///< set name in decks, e.g. "fixed_base_mandible"
    std::vector<std::int32_t> nodes;        ///< sorted, exterior nodes of the region
    std::vector<Tri> faces;                 ///< exterior faces whose three nodes are all in `nodes`
    std::array<bool, 3> fixedDofs{true, true, true};
};

/// A force spread as a uniform traction over a patch of exterior faces: each writer derives
/// consistent nodal forces (or a traction) from it, so the resultant is exactly totalForceN.
struct SurfaceLoad {
    std::string name;                       ///< set/surface name in decks, e.g. "load_tooth_24"
    int unn = 0;                            ///< tooth loaded, 0 for loads not on a tooth
    std::vector<Tri> faces;                 ///< outward exterior faces of the patch
    Vec3 totalForceN = Vec3::Zero();        ///< resultant force, N
    double areaMm2 = 0;                     ///< patch area
    Vec3 targetMm = Vec3::Zero();           ///< where the load was aimed (e.g. c + 4 mm labial)
    std::int32_t referenceNode = -1;        ///< patch centre node (displacement reported there), -1 none
    Vec3 traction() const { return areaMm2 > 0 ? Vec3(totalForceN / areaMm2) : Vec3::Zero(); }  ///< MPa
};

struct FeScenario {
    std::string name;                       ///< "tipping" | "biting"
    std::vector<FixedSet> fixed;
    std::vector<SurfaceLoad> loads;
    bool contact = false;                   ///< tooth-tooth contact left to the solver
    /// Biting: the decks are written with the mandible moved by this (its crowns then touch the
    /// maxilla's, fe/CloseBite.h); zero for other scenarios.
    Vec3 mandibleOffsetMm = Vec3::Zero();
    std::vector<std::string> notes;         ///< what a person should know (teeth skipped, ...)
};

struct TippingOptions {
    double forceN = 1.0;                    ///< per tooth, lingual
    double loadOffsetMm = 4.0;              ///< load aimed at c + offset * labial
    double patchRadiusMm = 1.0;             ///< faces whose centroid lies this close to the load node
    std::size_t minPatchFaces = 4;          ///< the radius grows (x1.5, up to 4x) until reached
    double mandibleBaseMm = 3.0;            ///< mandible: bone nodes this close to its lowest point are fixed
    double maxillaBaseMm = 6.0;             ///< maxilla: bone nodes this close to its highest point are fixed
};

/// Uncontrolled tipping: the base of every bone region fixed; on every tooth that has axes, a
/// force of forceN against its labial axis (lingual) over a patch of exposed crown faces (exterior
/// faces of the tooth whose normal points labially) around the crown node nearest to
/// c + loadOffsetMm * labial. "Up" is the mean occlusal axis of the mandible's teeth (the opposite
/// for the maxilla), or +z when a jaw has no axes.
/// Teeth without axes, or without a labially facing exposed face, are skipped with a note.
/// Throws Error when the mesh has no bone region or no tooth could be loaded.
/// Cost: one face adjacency plus O(exterior faces x teeth).
FeScenario tippingScenario(const TetMesh& mesh, const std::map<int, ToothAxes>& axes, const TippingOptions& options = {});

struct BitingOptions {
    double forceN = 200.0;                  ///< upward resultant on the mandible base
    double maxillaTopMm = 6.0;              ///< maxilla bone nodes this close to its top are fixed
    double mandibleBaseMm = 3.0;            ///< mandible bone nodes this close to its bottom carry the load
};

/// Biting, both jaws in one mesh: maxilla fixed at its top; the mandible base held in the two
/// horizontal coordinate directions (the vertical one is the coordinate axis nearest the
/// mandible-to-maxilla direction) and pushed up by forceN as a uniform traction; contact between
/// the teeth of the two jaws is left to the solver (contact = true). The jaws start in contact:
/// mandibleOffsetMm moves the mandible up by the gap between the crowns (biteGapMm; noted), since
/// a static solve cannot begin with the mandible free and touching nothing.
/// Throws Error unless the mesh holds both bones.
FeScenario bitingScenario(const TetMesh& mesh, const BitingOptions& options = {});

}  // namespace jawmesh
