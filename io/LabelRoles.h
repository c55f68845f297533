// What each segment of a label volume is (issue #23): bone, a tooth or its PDL by UNN, or ignored.
// From <case>/input/<jaw>/labels.json when present:
//   {"labels": {"1": "bone", "2": "tooth_18", "102": "pdl_18", "7": "ignore"}, "pdl": "generate"}
// (keys: label values; values: bone, tooth_<UNN>, pdl_<UNN>, ignore), else from the segments' own
// names (3D Slicer): "mandible", "maxilla", "bone", "jaw", "Tooth 24", "tooth_24", "tooth24",
// "PDL 24", "pdl_24" (case, spaces, '-' and '_' do not matter).
#pragma once

#include "io/LabelVolume.h"
#include "io/Labels.h"

#include <string>
#include <vector>

namespace jawmesh {

struct LabelRole {
    enum class Kind { Bone, Tooth, Pdl, Ignore };
    Kind kind = Kind::Ignore;
    int unn = 0;  ///< tooth and PDL only
};

/// What to do with segmented PDL labels: keep them as the PDL, or mesh them as bone and carve the
/// PDL at the requested thickness as for surfaces.
enum class PdlLabels { Keep, Generate };

struct LabelAssignment {
    std::vector<LabelRole> roles;  ///< one per volume.segments entry
    PdlLabels pdl = PdlLabels::Keep;
    bool hasPdl = false;           ///< some segment is a PDL
};

/// The role a name gives, or false when the name says none of the above.
bool roleFromName(const std::string& name, LabelRole& role);

/// Roles of every segment of `volume` for a jaw. Throws Error naming labels.json (or the volume)
/// for: malformed JSON, a key that is not an integer, a value that is no role, a "pdl" other than
/// keep / generate; segments left without a role (listing each value, name and voxel count); a
/// tooth or PDL whose UNN is not of this jaw; a PDL without its tooth; no bone or no tooth. Several
/// segments may share a role (enamel and dentin of one tooth, cortical and cancellous bone): they
/// are meshed as their union.
LabelAssignment assignLabelRoles(const LabelVolume& volume, Jaw jaw, const std::string& labelsJsonPath);

}  // namespace jawmesh
