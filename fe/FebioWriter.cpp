// Implements fe/FebioWriter.h; what it computes, its rules and its contract are documented there.
#include "fe/FebioWriter.h"

#include "fe/ExteriorFaces.h"
#include "fe/QuadraticTets.h"
#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/NumberText.h"

#include <map>
#include <ostream>
#include <set>

namespace jawmesh {
namespace {

/// At the file's precision (15 digits).
void writeVec(std::ostream& out, const Vec3& v) {
    for (int i = 0; i < 3; ++i) {
        if (i) out << ',';
        writeNumber(out, v[i], 15);
    }
}

/// A surface as tri3 (or tri6 with the faces' mid-edge nodes, FEBio's order: corners, then the
/// mid-nodes of edges 01, 12, 20).
void writeSurface(std::ostream& out, const std::string& name, const std::vector<Tri>& faces, const EdgeMidNodes* mids) {
    out << "\t\t<Surface name=\"" << name << "\">\n";
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const Tri& t = faces[f];
        out << "\t\t\t<" << (mids ? "tri6" : "tri3") << " id=\"" << f + 1 << "\">" << t[0] + 1 << "," << t[1] + 1 << "," << t[2] + 1;
        if (mids)
            for (int i = 0; i < 3; ++i) out << "," << mids->at(edgeKey(t[static_cast<std::size_t>(i)], t[static_cast<std::size_t>((i + 1) % 3)])) + 1;
        out << "</" << (mids ? "tri6" : "tri3") << ">\n";
    }
    out << "\t\t</Surface>\n";
}

}  // namespace

void writeFebioDeck(const TetMesh& mesh, const FeScenario& s, const MaterialTable& materials, const std::string& path,
                    const FebioOptions& o) {
    if (o.order != 1 && o.order != 2) throw Error(path, "element order must be 1 (tet4) or 2 (tet10)");
    if (mesh.labels.size() != mesh.tets.size()) throw Error(path, "one label per tet expected");
    EdgeMidNodes mids;
    MixedTetMesh quadratic;
    if (o.order == 2) quadratic = quadraticTetMesh(mesh, &mids);
    const std::vector<Vec3>& nodes = o.order == 2 ? quadratic.nodes : mesh.nodes;
    const EdgeMidNodes* faceMids = o.order == 2 ? &mids : nullptr;

    std::map<Label, std::vector<std::size_t>> tetsOf;
    std::set<LabelKind> kinds;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        labelName(mesh.labels[t]);  // throws for unknown labels before anything is written
        tetsOf[mesh.labels[t]].push_back(t);
        kinds.insert(labelKind(mesh.labels[t]));
    }
    // Contact: the exposed crowns of each jaw (only for scenarios that ask for contact).
    std::map<Jaw, std::vector<Tri>> crowns;
    if (s.contact)
        for (const ExteriorFace& f : exteriorFaces(mesh))
            if (isToothLike(labelKind(f.label))) crowns[jawOfTooth(labelUnn(f.label))].push_back(f.nodes);

    writeFileAtomically(path, [&](std::ostream& out) {
        out.precision(15);
        out << "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n"
            << "<!-- jawmesh " << s.name << " scenario. Units: mm, N, MPa, tonne/mm^3, s. Regions as in labels.json. -->\n";
        for (const std::string& note : s.notes) out << "<!-- note: " << note << " -->\n";
        out << "<febio_spec version=\"4.0\">\n\t<Module type=\"solid\"/>\n";
        out << "\t<Control>\n\t\t<analysis>STATIC</analysis>\n\t\t<time_steps>" << o.timeSteps << "</time_steps>\n"
            << "\t\t<step_size>" << 1.0 / o.timeSteps << "</step_size>\n"
            << "\t\t<plot_level>PLOT_MAJOR_ITRS</plot_level>\n\t\t<output_level>OUTPUT_MAJOR_ITRS</output_level>\n"
            << "\t\t<time_stepper type=\"default\">\n\t\t\t<max_retries>5</max_retries>\n\t\t\t<opt_iter>11</opt_iter>\n"
            << "\t\t\t<dtmin>0</dtmin>\n\t\t\t<dtmax>" << 1.0 / o.timeSteps << "</dtmax>\n\t\t</time_stepper>\n"
            << "\t\t<solver type=\"solid\">\n\t\t\t<symmetric_stiffness>symmetric</symmetric_stiffness>\n"
            << "\t\t\t<max_refs>15</max_refs>\n\t\t\t<diverge_reform>1</diverge_reform>\n\t\t</solver>\n\t</Control>\n";
        out << "\t<Globals>\n\t\t<Constants>\n\t\t\t<T>0</T>\n\t\t\t<P>0</P>\n\t\t\t<R>0</R>\n\t\t\t<Fc>0</Fc>\n\t\t</Constants>\n\t</Globals>\n";
        out << "\t<Material>\n";
        std::map<LabelKind, int> materialId;
        for (LabelKind kind : kinds) {
            const int id = static_cast<int>(materialId.size()) + 1;
            materialId[kind] = id;
            const Material& m = materialOf(materials, kind);
            out << "\t\t<material id=\"" << id << "\" name=\"" << materialName(kind) << "\" type=\"neo-Hookean\">\n"
                << "\t\t\t<density>" << m.densityTonnePerMm3 << "</density>\n\t\t\t<E>" << m.youngMpa << "</E>\n"
                << "\t\t\t<v>" << m.poisson << "</v>\n\t\t</material>\n";
        }
        out << "\t</Material>\n\t<Mesh>\n\t\t<Nodes name=\"all\">\n";
        for (std::size_t v = 0; v < nodes.size(); ++v) {
            out << "\t\t\t<node id=\"" << v + 1 << "\">";
            writeVec(out, nodes[v]);
            out << "</node>\n";
        }
        out << "\t\t</Nodes>\n";
        std::size_t elementId = 0;
        for (const auto& [label, tets] : tetsOf) {
            out << "\t\t<Elements type=\"" << (o.order == 2 ? "tet10" : "tet4") << "\" name=\"" << labelName(label) << "\">\n";
            for (std::size_t t : tets) {
                out << "\t\t\t<elem id=\"" << ++elementId << "\">";
                if (o.order == 2) {
                    const Tet10 e = abaqusOrderFromGmsh(quadratic.tets[t]);  // FEBio's tet10 order is Abaqus's
                    for (std::size_t i = 0; i < 10; ++i) out << (i ? "," : "") << e[i] + 1;
                } else {
                    for (std::size_t i = 0; i < 4; ++i) out << (i ? "," : "") << mesh.tets[t][i] + 1;
                }
                out << "</elem>\n";
            }
            out << "\t\t</Elements>\n";
        }
        for (const FixedSet& f : s.fixed) {
            out << "\t\t<NodeSet name=\"" << f.name << "\">";
            for (std::size_t i = 0; i < f.nodes.size(); ++i) out << (i ? "," : "") << f.nodes[i] + 1;
            out << "</NodeSet>\n";
        }
        for (const SurfaceLoad& l : s.loads) writeSurface(out, l.name, l.faces, faceMids);
        for (const auto& [jaw, faces] : crowns) writeSurface(out, "crowns_" + jawName(jaw), faces, faceMids);
        if (crowns.size() == 2)
            out << "\t\t<SurfacePair name=\"occlusal_contact\">\n\t\t\t<primary>crowns_mandible</primary>\n"
                << "\t\t\t<secondary>crowns_maxilla</secondary>\n\t\t</SurfacePair>\n";
        out << "\t</Mesh>\n\t<MeshDomains>\n";
        for (const auto& [label, tets] : tetsOf)
            out << "\t\t<SolidDomain name=\"" << labelName(label) << "\" mat=\"" << materialName(labelKind(label)) << "\"/>\n";
        out << "\t</MeshDomains>\n\t<Boundary>\n";
        for (const FixedSet& f : s.fixed)
            out << "\t\t<bc name=\"" << f.name << "\" node_set=\"" << f.name << "\" type=\"zero displacement\">\n"
                << "\t\t\t<x_dof>" << f.fixedDofs[0] << "</x_dof>\n\t\t\t<y_dof>" << f.fixedDofs[1] << "</y_dof>\n"
                << "\t\t\t<z_dof>" << f.fixedDofs[2] << "</z_dof>\n\t\t</bc>\n";
        out << "\t</Boundary>\n\t<Loads>\n";
        for (const SurfaceLoad& l : s.loads) {
            out << "\t\t<!-- resultant " << l.totalForceN.x() << ", " << l.totalForceN.y() << ", " << l.totalForceN.z()
                << " N over " << l.areaMm2 << " mm^2 -->\n"
                << "\t\t<surface_load name=\"" << l.name << "\" surface=\"" << l.name << "\" type=\"traction\">\n"
                << "\t\t\t<scale lc=\"1\">1</scale>\n\t\t\t<traction>";
            writeVec(out, l.traction());
            out << "</traction>\n\t\t</surface_load>\n";
        }
        out << "\t</Loads>\n";
        if (crowns.size() == 2)
            out << "\t<Contact>\n\t\t<contact name=\"occlusal_contact\" surface_pair=\"occlusal_contact\" type=\"sliding-elastic\">\n"
                << "\t\t\t<laugon>0</laugon>\n\t\t\t<penalty>1</penalty>\n\t\t\t<auto_penalty>1</auto_penalty>\n"
                << "\t\t\t<two_pass>0</two_pass>\n\t\t\t<symmetric_stiffness>0</symmetric_stiffness>\n"
                << "\t\t</contact>\n\t</Contact>\n";
        out << "\t<LoadData>\n\t\t<load_controller id=\"1\" name=\"ramp\" type=\"loadcurve\">\n"
            << "\t\t\t<interpolate>LINEAR</interpolate>\n\t\t\t<points>\n\t\t\t\t<pt>0,0</pt>\n\t\t\t\t<pt>1,1</pt>\n"
            << "\t\t\t</points>\n\t\t</load_controller>\n\t</LoadData>\n";
        out << "\t<Output>\n\t\t<plotfile type=\"febio\">\n\t\t\t<var type=\"displacement\"/>\n\t\t\t<var type=\"stress\"/>\n"
            << "\t\t\t<var type=\"effective stress\"/>\n\t\t</plotfile>\n\t</Output>\n</febio_spec>\n";
    }, false);
}

}  // namespace jawmesh
