// Implements fe/PolyfemWriter.h; what it computes, its rules and its contract are documented there.
#include "fe/PolyfemWriter.h"

#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/GmshWriter.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <numeric>
#include <set>

namespace fs = std::filesystem;

namespace jawmesh {

std::vector<std::string> writePolyfemDeck(const TetMesh& mesh, const FeScenario& s, const MaterialTable& materials,
                                          const std::string& jsonPath, const PolyfemOptions& o) {
    if (mesh.labels.size() != mesh.tets.size()) throw Error(jsonPath, "one label per tet expected");
    const fs::path json(jsonPath);
    const std::string stem = json.stem().string();
    const fs::path dir = json.parent_path();
    const std::string mshName = stem + ".msh", bodiesName = stem + "_bodies.txt", surfacesName = stem + "_surfaces.txt";

    // PolyFEM reads elements block by block (label order) and vertices by tag: sort the tets by
    // label and compact the nodes so both orders are the ones written here.
    std::vector<std::size_t> order(mesh.tets.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return mesh.labels[a] < mesh.labels[b]; });
    TetMesh sorted;
    std::vector<std::int32_t> index(mesh.nodes.size(), -1);
    for (std::size_t t : order) {
        Tet tet;
        for (std::size_t i = 0; i < 4; ++i) {
            auto& id = index[static_cast<std::size_t>(mesh.tets[t][i])];
            if (id < 0) {
                id = static_cast<std::int32_t>(sorted.nodes.size());
                sorted.nodes.push_back(mesh.nodes[static_cast<std::size_t>(mesh.tets[t][i])]);
            }
            tet[i] = id;
        }
        sorted.tets.push_back(tet);
        sorted.labels.push_back(mesh.labels[t]);
    }
    auto mapped = [&](const Tri& f) {
        Tri m;
        for (std::size_t i = 0; i < 3; ++i) {
            m[i] = index[static_cast<std::size_t>(f[i])];
            if (m[i] < 0) throw Error(jsonPath, "a boundary face uses a node that no tet uses");
        }
        return m;
    };

    nlohmann::json root;
    root["geometry"] = {{{"mesh", mshName}, {"volume_selection", bodiesName}, {"surface_selection", surfacesName}}};
    nlohmann::json materialsJson = nlohmann::json::array(), orders = nlohmann::json::array();
    for (Label label : std::set<Label>(sorted.labels.begin(), sorted.labels.end())) {
        const Material& m = materialOf(materials, label);
        materialsJson.push_back({{"id", label}, {"type", "NeoHookean"}, {"E", m.youngMpa}, {"nu", m.poisson}, {"rho", m.densityTonnePerMm3}});
        orders.push_back({{"id", label}, {"order", o.quadraticPdl && labelKind(label) == LabelKind::Pdl ? 2 : 1}});
    }
    root["materials"] = materialsJson;
    root["space"] = {{"discr_order", orders}};

    std::vector<std::pair<int, Tri>> surfaceRows;
    nlohmann::json dirichlet = nlohmann::json::array(), neumann = nlohmann::json::array();
    int nextId = 1;
    std::map<std::string, int> idOfFixed;
    for (const FixedSet& f : s.fixed) {
        const int id = nextId++;
        idOfFixed[f.name] = id;
        for (const Tri& t : f.faces) surfaceRows.push_back({id, mapped(t)});
        nlohmann::json bc = {{"id", id}, {"value", {0.0, 0.0, 0.0}}};
        if (!(f.fixedDofs[0] && f.fixedDofs[1] && f.fixedDofs[2])) bc["dimension"] = {f.fixedDofs[0], f.fixedDofs[1], f.fixedDofs[2]};
        dirichlet.push_back(bc);
    }
    for (const SurfaceLoad& l : s.loads) {
        int id = 0;
        for (const FixedSet& f : s.fixed)
            if (f.faces == l.faces) id = idOfFixed[f.name];
        if (id == 0) {
            id = nextId++;
            for (const Tri& t : l.faces) surfaceRows.push_back({id, mapped(t)});
        }
        const Vec3 traction = l.traction();
        neumann.push_back({{"id", id}, {"value", {traction.x(), traction.y(), traction.z()}}});
    }
    root["boundary_conditions"] = {{"dirichlet_boundary", dirichlet}, {"neumann_boundary", neumann}};
    root["contact"] = s.contact ? nlohmann::json{{"enabled", true}, {"dhat", o.contactDhatMm}} : nlohmann::json{{"enabled", false}};
    root["solver"] = {{"nonlinear", {{"max_iterations", 1000}}}};
    root["output"] = {{"paraview", {{"file_name", stem + ".vtu"}, {"options", {{"material", true}, {"body_ids", true}}}}}};
    root["jawmesh"] = {{"scenario", s.name},
                       {"units", "mm, N, MPa, tonne/mm^3"},
                       {"selections", "surface ids: dirichlet 1..; loads after (their traction in MPa)"},
                       {"notes", s.notes}};

    std::vector<std::string> written;
    writeGmsh(sorted, (dir / mshName).string());
    written.push_back((dir / mshName).string());
    writeFileAtomically((dir / bodiesName).string(), [&](std::ostream& out) {
        for (Label l : sorted.labels) out << l << "\n";
    }, false);
    written.push_back((dir / bodiesName).string());
    writeFileAtomically((dir / surfacesName).string(), [&](std::ostream& out) {
        for (const auto& [id, t] : surfaceRows) out << id << " " << t[0] << " " << t[1] << " " << t[2] << "\n";
    }, false);
    written.push_back((dir / surfacesName).string());
    writeFileAtomically(jsonPath, [&](std::ostream& out) { out << root.dump(2) << "\n"; }, false);
    written.push_back(jsonPath);
    return written;
}

}  // namespace jawmesh
