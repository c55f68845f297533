// Case folders in the Open-Full-Jaw input layout (docs/DESIGN.md):
//   <case>/input/<jaw>/bone/<jaw>.<ext>               jaw = mandible | maxilla, ext = stl|obj|ply|off
//   <case>/input/<jaw>/teeth/tooth_<UNN>.<ext>        one file per tooth (UNN 1..16 maxilla, 17..32 mandible)
//   <case>/input/<jaw>/teeth/all_teeth.obj            alternative: every tooth as a connected component
//                                                     (also accepted directly in <case>/input/<jaw>/)
//   <case>/input/<jaw>/teeth_axes_<jaw>.json          optional tooth axes
//   <case>/input/<jaw>/labels.<nrrd|nhdr|seg.nrrd|nii|nii.gz>   alternative to bone/ and teeth/: a
//   <case>/input/<jaw>/labels.json                    label volume, with its optional label names
//                                                     (io/LabelRoles.h); read by loadJawInput
// discoverCase() only looks at names; loadJaw() reads the surfaces, checks the units and numbers
// the teeth of an all_teeth.obj along the arch.
#pragma once

#include "io/ArchNumbering.h"
#include "io/Labels.h"
#include "io/Progress.h"
#include "io/SurfaceMesh.h"
#include "io/ToothAxes.h"

#include <map>
#include <string>
#include <vector>

namespace jawmesh {

/// The files of one jaw of a case.
struct JawCase {
    Jaw jaw = Jaw::Mandible;
    std::string folder;                    ///< <case>/input/<jaw>
    std::string bonePath;                  ///< input/<jaw>/bone/<jaw>.<ext>
    std::map<int, std::string> toothPaths; ///< UNN -> tooth file; empty when teethFromAllTeethObj
    std::string axesPath;                  ///< teeth_axes_<jaw>.json, empty when absent
    bool teethFromAllTeethObj = false;     ///< teeth come from one all_teeth.obj (numbered at load)
    std::string allTeethPath;              ///< that all_teeth.obj, empty otherwise
    std::string labelVolumePath;           ///< input/<jaw>/labels.<ext> when the jaw is a label volume
    std::string labelsJsonPath;            ///< its input/<jaw>/labels.json, empty when absent
};

/// Every jaw found in a case folder (mandible first).
struct CaseInfo {
    std::string root;            ///< the case folder as given
    std::vector<JawCase> jaws;   ///< at least one
};

/// Finds the jaws of a case folder by file names only (no file is read).
/// Throws Error(path, reason) when: the folder is missing, it has no input/ folder, input/ has no
/// mandible/ or maxilla/ folder, a jaw has no bone file or several (mandible.stl and mandible.obj),
/// a jaw has no teeth (unless it is a label volume; several label volumes, or one beside
/// surfaces, are refused), a tooth file name is not tooth_<UNN>.<ext>, a UNN is outside 1..32 or belongs
/// to the other jaw, a UNN appears twice (tooth_24.stl and tooth_24.obj), or a jaw has both
/// tooth_<UNN> files and an all_teeth.obj. Cost: a few directory listings.
CaseInfo discoverCase(const std::string& caseDir);

/// The tooth_<UNN>.<ext> surfaces of a teeth folder by UNN, as discoverCase names them (an
/// all_teeth.obj is skipped: its caller's). Throws Error as discoverCase does for a name without a
/// tooth number, a UNN outside 1..32 or of the other jaw, and a UNN given twice.
std::map<int, std::string> toothFilesIn(const std::string& teethDir, Jaw jaw);

/// The label volume of a jaw folder (<case>/input/<jaw>/labels.nrrd, .nhdr, .seg.nrrd, .nii or
/// .nii.gz), empty when there is none. Throws Error when there are several.
std::string labelVolumeIn(const std::string& jawDir);

struct LoadOptions {
    /// 0: automatic (coordinates must already be millimetres; a bounding-box diagonal below 1 or
    /// above 1000 is refused). > 0: every coordinate (and tooth crown centre) is multiplied by it
    /// and the unit check is skipped.
    double scale = 0.0;
};

/// The surfaces of one jaw, in millimetres.
struct JawSurfaces {
    Jaw jaw = Jaw::Mandible;
    SurfaceMesh bone;
    std::map<int, SurfaceMesh> teeth;     ///< by UNN
    std::map<int, ToothAxes> axes;        ///< by UNN; empty without an axes file
    std::vector<std::string> notes;       ///< things a person should know (numbering used, scaling, ...)
    /// A label map's segmented PDL is kept: `bone` leaves it out, so it is the gap between each
    /// root and its socket, which carving keeps (levelset/CarveGaps.h keptPdlCarveOptions).
    bool pdlKept = false;
    /// A label map's coarsest voxel spacing, mm (0 for surfaces): the input's own resolution, which
    /// the surface bounds must not exceed (cli/RunOptions.h simplifyOptionsFor).
    double labelVoxelMm = 0.0;
};

/// Reads every surface of a jaw (in parallel, TBB) and its axes; splits and numbers an all_teeth.obj
/// with numberTeethAlongArch(); applies LoadOptions::scale or the unit check.
/// Throws Error naming the file for unreadable or malformed files, for a case that does not look
/// like millimetres (with a hint to pass a scale), and for a negative or non-finite scale; Cancelled
/// when progress is cancelled. Cost: dominated by reading (about 0.1-0.4 s per million triangles).
JawSurfaces loadJaw(const JawCase& jawCase, const LoadOptions& options = {}, Progress& progress = noProgress());


/// The input file of a jaw case's bone, for messages (its label volume when the jaw is one).
std::string boneSource(const JawCase& jawCase);

/// Throws Error naming `file` unless options.scale is 0 (automatic) or a positive number.
void requireValidScale(const LoadOptions& options, const std::string& file);

/// The input file of tooth `unn` of a jaw case, for messages ("<all_teeth.obj> (tooth 24)" when
/// the teeth came from one file).
std::string toothSource(const JawCase& jawCase, int unn);

}  // namespace jawmesh
