// Structural validation of a labeled tet mesh: conformity between regions, manifoldness, element
// orientation, and the jaw's region layout (every expected tooth with its PDL; a PDL touches only
// its tooth, the bone and the outside; distinct teeth share no node).
#pragma once

#include "io/TetMesh.h"

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace jawmesh {

/// Counts per check. Every field under "violations" must be 0 for a valid mesh; the others
/// describe the mesh.
struct ValidationReport {
    // description
    std::size_t nodes = 0;
    std::size_t tets = 0;
    std::size_t unusedNodes = 0;
    std::size_t boundaryFaces = 0;    ///< faces of one tet (on the outside)
    std::size_t interfaceFaces = 0;   ///< faces shared by two tets of different labels
    std::size_t interiorFaces = 0;    ///< faces shared by two tets of the same label
    std::map<Label, std::size_t> tetsPerLabel;
    std::map<std::pair<Label, Label>, std::size_t> interfaceFacesPerPair;  ///< (lo, hi); hi/lo 0 = outside
    // violations
    std::size_t badIndices = 0;           ///< tets with a node index out of range or repeated
    std::size_t unknownLabels = 0;        ///< tets whose label is 0 or not a jaw label
    std::size_t sizeMismatch = 0;         ///< 1 when labels.size() != tets.size()
    std::size_t nonManifoldFaces = 0;     ///< faces shared by more than two tets
    std::size_t duplicateNodes = 0;       ///< nodes at exactly the position of a lower-indexed node
    std::size_t coincidentFaces = 0;      ///< distinct faces with the same three node positions
    std::size_t invertedTets = 0;         ///< negative orientation
    std::size_t degenerateTets = 0;       ///< |6 V| <= 1e-9 * (longest edge)^3
    std::vector<int> missingTeeth;        ///< expected UNN without tooth tets
    std::vector<int> missingPdls;         ///< expected UNN without PDL tets
    std::vector<int> unfusedImplants;     ///< expected UNN whose implant shares no face with the bone
    std::size_t pdlForeignContacts = 0;   ///< faces between pdl_i and anything but tooth_i, bone, outside
    std::size_t teethSharingNodes = 0;    ///< nodes used by regions of two different teeth
    std::vector<std::string> messages;    ///< one line per failed check, with an example location

    std::size_t violationCount() const;
    bool valid() const { return violationCount() == 0; }
};

/// Runs every check on `mesh`. `expectedTeethUnn` lists the teeth that must be present (with their
/// PDL), or an implant in their place (fused: sharing faces with the bone); empty skips the
/// presence check. Never throws for a bad mesh (that is what the report is
/// for). Cost: O(T log T) (parallel sorts of faces and nodes); about 1-2 s for 1 M tets on two
/// cores; result independent of the thread count.
ValidationReport validateTetMesh(const TetMesh& mesh, const std::vector<int>& expectedTeethUnn);

/// validateTetMesh, then throws Error("tet mesh", <every message>) if any check failed.
ValidationReport requireValid(const TetMesh& mesh, const std::vector<int>& expectedTeethUnn);

/// The report as JSON (for run.json and evaluation): counts, per-label tet counts, messages.
nlohmann::json toJson(const ValidationReport& report);

}  // namespace jawmesh
