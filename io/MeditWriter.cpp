// Implements io/MeditWriter.h; what it computes, its rules and its contract are documented there.
#include "io/MeditWriter.h"

#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/NumberText.h"

#include <ostream>

namespace jawmesh {

void writeMedit(const TetMesh& mesh, const std::string& path, const MeditTriangles* triangles) {
    if (mesh.labels.size() != mesh.tets.size())
        throw Error(path, std::to_string(mesh.labels.size()) + " labels for " + std::to_string(mesh.tets.size()) + " tets");
    const auto nn = static_cast<std::int64_t>(mesh.nodes.size());
    auto checkIndex = [&](std::int32_t v, const char* what, std::size_t i) {
        if (v < 0 || v >= nn) throw Error(path, std::string(what) + " " + std::to_string(i) + " has a node index out of range");
    };
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        for (auto v : mesh.tets[t]) checkIndex(v, "tet", t);
    const bool withTriangles = triangles && !triangles->triangles.empty();
    if (withTriangles) {
        if (triangles->references.size() != triangles->triangles.size())
            throw Error(path, "triangle references do not match the triangles");
        for (std::size_t t = 0; t < triangles->triangles.size(); ++t)
            for (auto v : triangles->triangles[t]) checkIndex(v, "triangle", t);
    }
    writeFileAtomically(path, [&](std::ostream& out) {
        out << "MeshVersionFormatted 2\nDimension 3\n\nVertices\n" << mesh.nodes.size() << '\n';
        for (const Vec3& p : mesh.nodes) {
            writeNumber(out, p.x()), out << ' ';
            writeNumber(out, p.y()), out << ' ';
            writeNumber(out, p.z()), out << " 0\n";
        }
        out << "\nTetrahedra\n" << mesh.tets.size() << '\n';
        for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
            const Tet& e = mesh.tets[t];
            out << e[0] + 1 << ' ' << e[1] + 1 << ' ' << e[2] + 1 << ' ' << e[3] + 1 << ' ' << mesh.labels[t] << '\n';
        }
        if (withTriangles) {
            out << "\nTriangles\n" << triangles->triangles.size() << '\n';
            for (std::size_t t = 0; t < triangles->triangles.size(); ++t) {
                const Tri& f = triangles->triangles[t];
                out << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << ' ' << triangles->references[t] << '\n';
            }
        }
        out << "\nEnd\n";
    });
}

}  // namespace jawmesh
