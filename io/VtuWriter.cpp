// Implements io/VtuWriter.h; what it computes, its rules and its contract are documented there.
#include "io/VtuWriter.h"

#include "io/AtomicFile.h"
#include "io/Error.h"

#include <cstring>
#include <ostream>
#include <vector>

namespace jawmesh {
namespace {

struct Array {
    std::string xml;           // the DataArray element without its offset
    std::vector<char> bytes;   // payload
};

template <class T>
Array makeArray(const std::string& type, const std::string& name, int components, const std::vector<T>& values) {
    Array a;
    a.xml = "<DataArray type=\"" + type + "\" Name=\"" + name + "\"" +
            (components > 1 ? " NumberOfComponents=\"" + std::to_string(components) + "\"" : std::string()) +
            " format=\"appended\"";
    a.bytes.resize(values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(a.bytes.data(), values.data(), a.bytes.size());
    return a;
}

}  // namespace

void writeVtu(const TetMesh& mesh, const std::string& path) {
    if (mesh.labels.size() != mesh.tets.size())
        throw Error(path, std::to_string(mesh.labels.size()) + " labels for " + std::to_string(mesh.tets.size()) + " tets");
    const std::size_t nn = mesh.nodes.size(), nt = mesh.tets.size();
    std::vector<double> points(3 * nn);
    for (std::size_t i = 0; i < nn; ++i)
        for (int k = 0; k < 3; ++k) points[3 * i + static_cast<std::size_t>(k)] = mesh.nodes[i][k];
    std::vector<std::int64_t> connectivity(4 * nt), offsets(nt);
    for (std::size_t t = 0; t < nt; ++t) {
        for (std::size_t k = 0; k < 4; ++k) {
            const std::int32_t v = mesh.tets[t][k];
            if (v < 0 || static_cast<std::size_t>(v) >= nn) throw Error(path, "tet " + std::to_string(t) + " has a node index out of range");
            connectivity[4 * t + k] = v;
        }
        offsets[t] = static_cast<std::int64_t>(4 * (t + 1));
    }
    const std::vector<std::uint8_t> types(nt, 10);  // VTK_TETRA
    const std::vector<std::int32_t> labels(mesh.labels.begin(), mesh.labels.end());

    Array pointsArray = makeArray("Float64", "Points", 3, points);
    Array conn = makeArray("Int64", "connectivity", 1, connectivity);
    Array offs = makeArray("Int64", "offsets", 1, offsets);
    Array typ = makeArray("UInt8", "types", 1, types);
    Array lab = makeArray("Int32", "label", 1, labels);

    writeFileAtomically(path, [&](std::ostream& out) {
        std::uint64_t offset = 0;
        auto element = [&](const Array& a) {
            out << "        " << a.xml << " offset=\"" << offset << "\"/>\n";
            offset += sizeof(std::uint64_t) + a.bytes.size();
        };
        out << "<?xml version=\"1.0\"?>\n"
            << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
            << "  <UnstructuredGrid>\n"
            << "    <Piece NumberOfPoints=\"" << nn << "\" NumberOfCells=\"" << nt << "\">\n"
            << "      <Points>\n";
        element(pointsArray);
        out << "      </Points>\n      <Cells>\n";
        element(conn);
        element(offs);
        element(typ);
        out << "      </Cells>\n      <CellData Scalars=\"label\">\n";
        element(lab);
        out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n    _";
        for (const Array* a : {&pointsArray, &conn, &offs, &typ, &lab}) {
            const std::uint64_t n = a->bytes.size();
            out.write(reinterpret_cast<const char*>(&n), sizeof n);
            out.write(a->bytes.data(), static_cast<std::streamsize>(a->bytes.size()));
        }
        out << "\n  </AppendedData>\n</VTKFile>\n";
    });
}

}  // namespace jawmesh
