// Clinical what-ifs on one jaw (issue #24): the edits of an edit file (io/Edits.h) applied in order
// to the jaw's level sets and the carve's options, before carving. Carving then restores what it
// guarantees on the edited anatomy (teeth apart, a PDL between every root and the bone, its cap at
// the crest), so no edit has to repair those itself.
//   extract        the tooth's level set is dropped; a healed socket fills with bone (HealSocket.h)
//   bone_loss      the crest around the teeth is lowered along their axes (LowerCrest.h)
//   pdl_thickness  the tooth's own PDL thickness or profile (CarveOptions::toothPdl)
//   implant        the socket heals, an implant goes in along the tooth's axis (ImplantBody.h)
//                  and carving fuses it to the bone (CarveOptions::implants); refused when it
//                  would leave the bone or reach another tooth
#pragma once

#include "io/Edits.h"
#include "io/Progress.h"
#include "levelset/CarveGaps.h"
#include "levelset/JawLevelSets.h"

#include <nlohmann/json.hpp>

namespace jawmesh {

/// Applies `edits` to `levelSets` (the bone grid and the teeth are replaced, not modified in place)
/// and to `carve` (axes from carve.axes where the case has them, else from the tooth's shape,
/// ToothLongAxis.h). Returns the record run.json keeps ({"file", "applied"}): per edit what it measured (crest heights
/// before and after, the healed socket's level and volume). Throws Error naming the edit file and
/// entry for an edit that cannot apply (a tooth not in the jaw, a loss deeper than a root);
/// Cancelled. Deterministic.
nlohmann::json applyEdits(const EditList& edits, JawLevelSets& levelSets, CarveOptions& carve,
                          Progress& progress = noProgress());

}  // namespace jawmesh
