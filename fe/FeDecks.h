// The FE decks of a meshed jaw in the output layout (docs/DESIGN.md): <out>/<jaw>/simulation/
// <scenario>.feb, <scenario>.inp, <scenario>_polyfem.json (+ its .msh and selection files).
// The entry point the pipeline and `jawmesh fe` call.
#pragma once

#include "fe/Materials.h"
#include "fe/Scenario.h"
#include "io/TetMesh.h"
#include "io/ToothAxes.h"

#include <map>
#include <set>
#include <string>
#include <vector>

namespace jawmesh {

struct FeDeckOptions {
    std::set<std::string> formats{"feb", "polyfem", "inp"};  ///< any of feb | polyfem | inp
    int order = 1;               ///< element order of .feb and .inp (PolyFEM: quadratic PDL always)
    MaterialTable materials;
    TippingOptions tipping;
    BitingOptions biting;
};

/// Tooth axes for the teeth of `mesh`: those of `given` when it has a tooth, else computed from the
/// tooth and bone surfaces of the mesh (toothAxesFromShape per jaw). `notes` (may be null) says
/// which teeth got computed axes.
std::map<int, ToothAxes> axesForMesh(const TetMesh& mesh, const std::map<int, ToothAxes>& given,
                                     std::vector<std::string>* notes = nullptr);

/// Writes `scenario` in every format of options.formats into <outJawDir>/simulation/:
/// <name>.inp, <name>.feb, <name>_polyfem.json (+ _polyfem.msh, _polyfem_bodies.txt,
/// _polyfem_surfaces.txt), on `mesh` with the mandible moved by scenario.mandibleOffsetMm (biting).
/// Returns the paths written. Throws Error for an unknown format or I/O failure.
std::vector<std::string> writeScenarioDecks(const TetMesh& mesh, FeScenario& scenario, const std::string& outJawDir,
                                            const FeDeckOptions& options = {});

/// The default decks of `jawmesh run`: the tipping scenario (1 N lingual per tooth) with axes from
/// axesForMesh(mesh, axes), in every format of options.formats, plus simulation/tipping_axes.json
/// (the axes used, same JSON shape as the case's). Returns the paths written; `notes`, when given,
/// receives the scenario's notes (the decks carry them as comments): computed axes, uncertain
/// ones (fe/ToothAxesFromShape.h), teeth not loaded. Throws Error when no tooth can be loaded, or
/// on I/O failure.
std::vector<std::string> writeTippingDecks(const TetMesh& mesh, const std::map<int, ToothAxes>& axes,
                                           const std::string& outJawDir, const FeDeckOptions& options = {},
                                           std::vector<std::string>* notes = nullptr);

}  // namespace jawmesh
