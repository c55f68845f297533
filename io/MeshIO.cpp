// Format dispatch plus the binary STL reader/writer (the hot path: segmentation exports are
// binary STL of millions of triangles). The other formats live in their own files.
// TODO(io): ASCII STL, OBJ, PLY, OFF readers; PLY/OBJ writers; full malformed-input checks.
#include "io/MeshIO.h"

#include "io/AtomicFile.h"
#include "io/Error.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <unordered_map>

namespace jawmesh {
namespace {

std::string lowerExtension(const std::string& path) {
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos) return {};
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string readWholeFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "cannot open file");
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) throw Error(path, "cannot read file size");
    std::string data(static_cast<std::size_t>(size), '\0');
    in.seekg(0);
    in.read(data.data(), size);
    if (!in) throw Error(path, "read failed");
    return data;
}

struct VertexKeyHash {
    std::size_t operator()(const std::array<float, 3>& k) const {
        std::uint32_t b[3];
        std::memcpy(b, k.data(), sizeof b);
        std::size_t h = b[0];
        h = h * 0x9E3779B97F4A7C15ull ^ b[1];
        h = h * 0x9E3779B97F4A7C15ull ^ b[2];
        return h;
    }
};

SurfaceMesh readBinaryStl(const std::string& path, const std::string& data) {
    if (data.size() < 84) throw Error(path, "binary STL shorter than its 84-byte header");
    std::uint32_t count = 0;
    std::memcpy(&count, data.data() + 80, 4);
    const std::uint64_t needed = 84ull + 50ull * count;
    if (data.size() < needed)
        throw Error(path, "binary STL header promises " + std::to_string(count) + " triangles but the file holds only " +
                              std::to_string((data.size() - 84) / 50));
    if (count == 0) throw Error(path, "STL file has no triangles");
    SurfaceMesh mesh;
    mesh.triangles.resize(count);
    mesh.vertices.reserve(count / 2 + 16);
    // Welding identical float positions recovers the connectivity STL throws away.
    std::unordered_map<std::array<float, 3>, std::int32_t, VertexKeyHash> index;
    index.reserve(count);
    const char* p = data.data() + 84;
    for (std::uint32_t t = 0; t < count; ++t, p += 50) {
        for (int c = 0; c < 3; ++c) {
            std::array<float, 3> key;
            std::memcpy(key.data(), p + 12 + 12 * c, 12);
            for (float v : key)
                if (!std::isfinite(v)) throw Error(path, "triangle " + std::to_string(t) + " has a NaN or infinite coordinate");
            for (float& v : key)
                if (v == 0.0f) v = 0.0f;  // -0 and +0 are the same point
            auto [it, inserted] = index.try_emplace(key, static_cast<std::int32_t>(mesh.vertices.size()));
            if (inserted) mesh.vertices.emplace_back(key[0], key[1], key[2]);
            mesh.triangles[t][static_cast<std::size_t>(c)] = it->second;
        }
    }
    return mesh;
}

void writeBinaryStl(const SurfaceMesh& mesh, std::ostream& out) {
    char header[80] = {};
    std::snprintf(header, sizeof header, "jawmesh binary STL, millimetres");
    out.write(header, 80);
    const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
    out.write(reinterpret_cast<const char*>(&count), 4);
    char record[50] = {};
    for (const Tri& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
        const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
        Vec3 n = (b - a).cross(c - a);
        const double len = n.norm();
        if (len > 0) n /= len;
        const float values[12] = {float(n.x()), float(n.y()), float(n.z()), float(a.x()), float(a.y()), float(a.z()),
                                  float(b.x()), float(b.y()), float(b.z()), float(c.x()), float(c.y()), float(c.z())};
        std::memcpy(record, values, 48);
        out.write(record, 50);
    }
}

}  // namespace

SurfaceMesh readSurface(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext != "stl") throw Error(path, "unsupported surface format '." + ext + "'");
    const std::string data = readWholeFile(path);
    if (data.empty()) throw Error(path, "file is empty");
    return readBinaryStl(path, data);
}

void writeSurface(const SurfaceMesh& mesh, const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext != "stl") throw Error(path, "cannot write surface format '." + ext + "'");
    writeFileAtomically(path, [&](std::ostream& out) { writeBinaryStl(mesh, out); });
}

}  // namespace jawmesh
