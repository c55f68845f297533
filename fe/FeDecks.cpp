// Implements fe/FeDecks.h; what it computes, its rules and its contract are documented there.
#include "fe/FeDecks.h"

#include "fe/CalculixWriter.h"
#include "fe/CloseBite.h"
#include "fe/FebioWriter.h"
#include "fe/PolyfemWriter.h"
#include "fe/ToothAxesFromShape.h"
#include "io/Error.h"
#include "tet/RegionSurfaces.h"

namespace jawmesh {

std::map<int, ToothAxes> axesForMesh(const TetMesh& mesh, const std::map<int, ToothAxes>& given,
                                     std::vector<std::string>* notes) {
    const std::map<Label, SurfaceMesh> surfaces = regionSurfaces(mesh);
    std::map<int, ToothAxes> axes;
    for (Jaw jaw : {Jaw::Mandible, Jaw::Maxilla}) {
        std::map<int, SurfaceMesh> teeth;
        bool missing = false;
        for (const auto& [label, surface] : surfaces)
            if (isToothLike(labelKind(label)) && jawOfTooth(labelUnn(label)) == jaw) {
                teeth[labelUnn(label)] = surface;
                missing |= !given.count(labelUnn(label));
            }
        if (teeth.empty()) continue;
        std::map<int, ToothAxes> computed;
        if (missing) {
            const auto bone = surfaces.find(boneLabel(jaw));
            computed = toothAxesFromShape(teeth, jaw, bone == surfaces.end() ? SurfaceMesh() : bone->second, {}, notes);
        }
        for (const auto& [unn, surface] : teeth) {
            const auto g = given.find(unn);
            if (g != given.end()) {
                axes[unn] = g->second;
            } else {
                axes[unn] = computed.at(unn);
                if (notes) notes->push_back("tooth " + std::to_string(unn) + ": axes computed from its shape");
            }
        }
    }
    return axes;
}

std::vector<std::string> writeScenarioDecks(const TetMesh& given, FeScenario& s, const std::string& outJawDir,
                                            const FeDeckOptions& o) {
    for (const std::string& f : o.formats)
        if (f != "feb" && f != "polyfem" && f != "inp") throw Error("unknown deck format '" + f + "' (feb, polyfem, inp)");
    const TetMesh closed = s.mandibleOffsetMm.isZero() ? TetMesh() : withMandibleMoved(given, s.mandibleOffsetMm);
    const TetMesh& mesh = s.mandibleOffsetMm.isZero() ? given : closed;
    const std::string dir = outJawDir + "/simulation/";
    std::vector<std::string> written;
    if (o.formats.count("inp")) {
        CalculixOptions c;
        c.order = o.order;
        writeCalculixDeck(mesh, s, o.materials, dir + s.name + ".inp", c);
        written.push_back(dir + s.name + ".inp");
    }
    if (o.formats.count("feb")) {
        FebioOptions f;
        f.order = o.order;
        writeFebioDeck(mesh, s, o.materials, dir + s.name + ".feb", f);
        written.push_back(dir + s.name + ".feb");
    }
    if (o.formats.count("polyfem")) {
        const auto files = writePolyfemDeck(mesh, s, o.materials, dir + s.name + "_polyfem.json");
        written.insert(written.end(), files.begin(), files.end());
    }
    return written;
}

std::vector<std::string> writeTippingDecks(const TetMesh& mesh, const std::map<int, ToothAxes>& given,
                                           const std::string& outJawDir, const FeDeckOptions& o,
                                           std::vector<std::string>* notesOut) {
    std::vector<std::string> notes;
    const std::map<int, ToothAxes> axes = axesForMesh(mesh, given, &notes);
    FeScenario s = tippingScenario(mesh, axes, o.tipping);
    s.notes.insert(s.notes.begin(), notes.begin(), notes.end());
    std::vector<std::string> written = writeScenarioDecks(mesh, s, outJawDir, o);
    const std::string axesPath = outJawDir + "/simulation/tipping_axes.json";
    writeToothAxes(axes, axesPath);
    written.push_back(axesPath);
    if (notesOut) *notesOut = s.notes;
    return written;
}

}  // namespace jawmesh
