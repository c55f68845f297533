// The evaluation report of one meshed jaw on disk: report.json, report.html (self-contained) and
// sections/*.png in a folder. Wiring only: tet/EvaluateMesh measures, filters/CrossSection cuts,
// io/ writes. Used by `jawmesh eval` and at the end of every `jawmesh run`.
#pragma once

#include "io/Case.h"
#include "io/Progress.h"
#include "io/TetMesh.h"
#include "tet/EvaluateMesh.h"

#include <nlohmann/json.hpp>

#include <string>

namespace jawmesh {

/// Evaluates `mesh` (against `input` when not null), renders a cross-section through every tooth
/// and one through the arch, and writes <dir>/report.json, <dir>/report.html and
/// <dir>/sections/<name>.png (each file written to a temporary name and renamed). `title` heads
/// the page. Returns the report. Throws Error on I/O failure, Cancelled.
nlohmann::json writeEvalReport(const TetMesh& mesh, const JawSurfaces* input, const EvalOptions& options,
                               const std::string& dir, const std::string& title, Progress& progress = noProgress());

/// The input surfaces of a jaw for evaluation, from either a jaw folder (<case>/input/<jaw>) or a
/// case folder (<case>; then `jaw` picks the jaw); a tooth given as overlapping shells comes back
/// as their union's boundary (levelset/UnionBoundary.h). Throws Error naming the folder when it is
/// neither or lacks that jaw, and whatever loadJawInput() throws.
JawSurfaces loadEvalInput(const std::string& path, Jaw jaw, const LoadOptions& load = {}, Progress& progress = noProgress());

/// What the report judges an edited jaw against (levelset/JawEdits.h's history, run.json's
/// "edits"): extracted teeth are expected absent (added to removedTeeth), an edited PDL is judged
/// against its own uniform thickness (a profile: measured only); the history goes into the report.
void judgeAgainstEdits(const nlohmann::json& history, EvalOptions& options, std::vector<int>& removedTeeth);

/// End-of-run report against the jaw's input: `loaded` when the run kept it (moved from; reading a
/// label volume and making its surfaces again took a tenth of a small run), else read again (a run
/// from carved grids has none); without the teeth an edit removed (`removedTeeth`). Writes
/// <outJawDir>/report/ titled "<case folder> <jaw>" and returns the short summary that goes into
/// run.json ("eval": verdict status and line, report path relative to outJawDir, seconds). Never
/// throws Error: a failed report is returned as {"error": ...} so the validated mesh of the run
/// stays the run's result. Throws Cancelled.
nlohmann::json runReport(const TetMesh& mesh, const JawCase& jawCase, const LoadOptions& load, JawSurfaces* loaded,
                         const EvalOptions& options, const std::vector<int>& removedTeeth, const std::string& outJawDir,
                         Progress& progress = noProgress());

}  // namespace jawmesh
