// Implements fe/CalculixWriter.h; what it computes, its rules and its contract are documented there.
#include "fe/CalculixWriter.h"

#include "fe/ConsistentNodalForces.h"
#include "fe/ExteriorFaces.h"
#include "fe/QuadraticTets.h"
#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/NumberText.h"

#include <algorithm>
#include <map>
#include <ostream>

namespace jawmesh {
namespace {

/// Abaqus data lines hold at most 16 entries.
void writeIdList(std::ostream& out, const std::vector<std::int32_t>& ids) {
    for (std::size_t i = 0; i < ids.size(); ++i) {
        out << ids[i] + 1 << ((i + 1) % 16 == 0 || i + 1 == ids.size() ? "\n" : ", ");
    }
}

/// Abaqus face label of a tet face given by the node it lies opposite (ExteriorFace::local):
/// S1 = nodes 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1; C3D10 numbers its faces alike.
const char* abaqusTetFace(std::int32_t oppositeNode) {
    static const char* const kFace[4] = {"S3", "S4", "S2", "S1"};
    return kFace[static_cast<std::size_t>(oppositeNode)];
}

}  // namespace

std::string calculixLoadPointSet(int unn) { return "loadpt_tooth_" + std::to_string(unn); }

void writeCalculixDeck(const TetMesh& mesh, const FeScenario& s, const MaterialTable& materials,
                       const std::string& path, const CalculixOptions& o) {
    if (o.order != 1 && o.order != 2) throw Error(path, "element order must be 1 (C3D4) or 2 (C3D10)");
    if (mesh.labels.size() != mesh.tets.size()) throw Error(path, "one label per tet expected");
    EdgeMidNodes mids;
    MixedTetMesh quadratic;
    if (o.order == 2) quadratic = quadraticTetMesh(mesh, &mids);
    const std::vector<Vec3>& nodes = o.order == 2 ? quadratic.nodes : mesh.nodes;

    std::map<Label, std::vector<std::size_t>> tetsOf;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        labelName(mesh.labels[t]);  // throws for unknown labels before anything is written
        tetsOf[mesh.labels[t]].push_back(t);
    }
    // Contact: the exposed crowns of each jaw, as faces of their elements.
    std::map<Jaw, std::vector<const ExteriorFace*>> crowns;
    std::vector<ExteriorFace> exterior;
    if (s.contact) {
        exterior = exteriorFaces(mesh);
        for (const ExteriorFace& f : exterior)
            if (isToothLike(labelKind(f.label))) crowns[jawOfTooth(labelUnn(f.label))].push_back(&f);
        if (crowns.size() != 2) throw Error(path, "the " + s.name + " scenario needs the crowns of both jaws for contact");
    }
    std::vector<char> used(nodes.size(), 0);
    for (const Tet& t : mesh.tets)
        for (std::int32_t v : t) used[static_cast<std::size_t>(v)] = 1;
    if (o.order == 2)
        for (std::size_t v = mesh.nodes.size(); v < nodes.size(); ++v) used[v] = 1;

    writeFileAtomically(path, [&](std::ostream& out) {
        out.precision(12);  // ccx reads at most 20 characters per field
        out << "** jawmesh " << s.name << " deck. Units: mm, N, MPa, tonne/mm^3, s.\n"
            << "** Regions are the labels of labels.json (element and node set per region).\n";
        for (const std::string& note : s.notes) out << "** note: " << note << "\n";
        out << "*HEADING\njawmesh " << s.name << " scenario\n";
        out << "*NODE, NSET=NALL\n";
        for (std::size_t v = 0; v < nodes.size(); ++v)
            if (used[v]) {
                out << v + 1;
                for (int i = 0; i < 3; ++i) {
                    out << ", ";
                    writeNumber(out, nodes[v][i], 12);
                }
                out << '\n';
            }
        for (const auto& [label, tets] : tetsOf) {
            out << "*ELEMENT, TYPE=" << (o.order == 2 ? "C3D10" : "C3D4") << ", ELSET=" << labelName(label) << "\n";
            for (std::size_t t : tets) {
                out << t + 1;
                if (o.order == 2) {
                    const Tet10 e = abaqusOrderFromGmsh(quadratic.tets[t]);
                    for (std::int32_t v : e) out << ", " << v + 1;  // 11 entries: one data line
                } else {
                    for (std::int32_t v : mesh.tets[t]) out << ", " << v + 1;
                }
                out << "\n";
            }
        }
        for (const auto& [label, tets] : tetsOf) {
            std::vector<std::int32_t> regionNodes;  // sorted and unique below (a std::set of them took 0.2 s)
            for (std::size_t t : tets) {
                if (o.order == 2) regionNodes.insert(regionNodes.end(), quadratic.tets[t].begin(), quadratic.tets[t].end());
                else regionNodes.insert(regionNodes.end(), mesh.tets[t].begin(), mesh.tets[t].end());
            }
            std::sort(regionNodes.begin(), regionNodes.end());
            regionNodes.erase(std::unique(regionNodes.begin(), regionNodes.end()), regionNodes.end());
            out << "*NSET, NSET=" << labelName(label) << "\n";
            writeIdList(out, regionNodes);
        }
        for (const FixedSet& f : s.fixed) {
            out << "*NSET, NSET=" << f.name << "\n";
            writeIdList(out, f.nodes);
        }
        std::vector<std::int32_t> loadPoints;
        for (const SurfaceLoad& l : s.loads)
            if (l.unn > 0 && l.referenceNode >= 0) {
                out << "*NSET, NSET=" << calculixLoadPointSet(l.unn) << "\n";
                writeIdList(out, {l.referenceNode});
                loadPoints.push_back(l.referenceNode);
            }
        if (!loadPoints.empty()) {
            out << "*NSET, NSET=" << kCalculixLoadPointsSet << "\n";
            writeIdList(out, loadPoints);
        }
        for (LabelKind kind : {LabelKind::Bone, LabelKind::Tooth, LabelKind::Pdl, LabelKind::Implant}) {
            const Material& m = materialOf(materials, kind);
            out << "*MATERIAL, NAME=" << materialName(kind) << "\n*DENSITY\n" << m.densityTonnePerMm3 << "\n"
                << "*HYPERELASTIC, NEO HOOKE\n" << neoHookeC10(m) << ", " << neoHookeD1(m) << "\n";
        }
        for (const auto& [label, tets] : tetsOf)
            out << "*SOLID SECTION, ELSET=" << labelName(label) << ", MATERIAL=" << materialName(labelKind(label)) << "\n";
        if (s.contact) {
            for (const auto& [jaw, faces] : crowns) {
                out << "*SURFACE, NAME=crowns_" << jawName(jaw) << ", TYPE=ELEMENT\n";
                for (const ExteriorFace* f : faces) out << f->tet + 1 << ", " << abaqusTetFace(f->local) << "\n";
            }
            // Frictionless penalty contact; the mandible's crowns are the slave side.
            out << "*SURFACE INTERACTION, NAME=occlusal_contact\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
                << o.contactStiffnessPerModulus * materials.tooth.youngMpa << "\n"
                << "*CONTACT PAIR, INTERACTION=occlusal_contact, TYPE=SURFACE TO SURFACE\ncrowns_mandible, crowns_maxilla\n";
        }
        out << "*STEP, NLGEOM, INC=" << o.maxIncrements << "\n*STATIC\n"
            << (s.contact ? o.contactInitialIncrement : o.initialIncrement) << ", 1.0, 1e-6, 1.0\n";
        out << "*BOUNDARY\n";
        for (const FixedSet& f : s.fixed)
            for (int d = 0; d < 3; ++d)
                if (f.fixedDofs[static_cast<std::size_t>(d)]) out << f.name << ", " << d + 1 << ", " << d + 1 << "\n";
        for (const SurfaceLoad& l : s.loads) {
            out << "** " << l.name << ": resultant " << l.totalForceN.x() << ", " << l.totalForceN.y() << ", "
                << l.totalForceN.z() << " N over " << l.faces.size() << " faces, " << l.areaMm2 << " mm^2\n*CLOAD\n";
            for (const auto& [node, f] : consistentNodalForces(l, nodes, o.order == 2 ? &mids : nullptr))
                for (int d = 0; d < 3; ++d)
                    if (f[d] != 0.0) out << node + 1 << ", " << d + 1 << ", " << f[d] << "\n";
        }
        out << "*NODE FILE\nU\n*EL FILE\nS\n";
        if (!loadPoints.empty()) out << "*NODE PRINT, NSET=" << kCalculixLoadPointsSet << "\nU\n";
        for (const auto& [label, tets] : tetsOf) out << "*EL PRINT, ELSET=" << labelName(label) << "\nS\n";
        out << "*END STEP\n";
    }, false);
}

}  // namespace jawmesh
