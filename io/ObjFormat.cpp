// Wavefront OBJ: "v" and "f" lines (v, v/vt, v//vn, v/vt/vn corners, negative indices relative
// to the vertices read so far); polygons are fan-triangulated, every other line is ignored.
#include "io/detail/MeshFormats.h"

#include <charconv>
#include <vector>

namespace jawmesh::detail {

SurfaceMesh readObj(const std::string& path, std::string_view data) {
    requireText(path, data, "OBJ");
    SurfaceMesh mesh;
    LineReader lines(data);
    std::string_view line;
    std::vector<std::int64_t> polygon;
    auto fail = [&](const std::string& what) {
        throw Error(path, "line " + std::to_string(lines.lineNumber()) + ": " + what);
    };
    while (lines.next(line)) {
        Tokens tokens(line);
        const std::string_view keyword = tokens.next();
        if (keyword == "v") {
            double xyz[3];
            for (double& v : xyz) {
                const std::string_view token = tokens.next();
                if (!parseDouble(token, v)) fail("vertex coordinate " + quoted(token) + " is not a finite number");
            }
            if (mesh.vertices.size() >= kMaxElements) fail("more than 2^31-1 vertices");
            mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
        } else if (keyword == "f") {
            polygon.clear();
            for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) {
                const std::string_view vertexPart = token.substr(0, token.find('/'));
                std::int64_t index = 0;
                if (!parseInt(vertexPart, index) || index == 0)
                    fail("face corner " + quoted(token) + " is not a valid vertex reference");
                const auto count = static_cast<std::int64_t>(mesh.vertices.size());
                if (index < 0) {
                    if (-index > count)
                        fail("relative vertex index " + std::to_string(index) + " reaches before the first vertex (" +
                             std::to_string(count) + " read so far)");
                    index = count + index;
                } else {
                    index -= 1;  // forward references are checked once every vertex is read
                    if (index >= static_cast<std::int64_t>(kMaxElements)) fail("vertex index out of range");
                }
                polygon.push_back(index);
            }
            if (polygon.size() < 3) fail("face with " + std::to_string(polygon.size()) + " corners (at least 3 needed)");
            for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
                if (mesh.triangles.size() >= kMaxElements) fail("more than 2^31-1 triangles");
                mesh.triangles.push_back({static_cast<std::int32_t>(polygon[0]), static_cast<std::int32_t>(polygon[i]),
                                          static_cast<std::int32_t>(polygon[i + 1])});
            }
        }
    }
    validateMesh(path, mesh);
    return mesh;
}

void writeObj(const SurfaceMesh& mesh, std::ostream& out) {
    std::string buffer;
    buffer.reserve(1 << 20);
    char number[64];
    auto flush = [&] {
        out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        buffer.clear();
    };
    buffer += "# jawmesh surface, millimetres\n";
    for (const Vec3& v : mesh.vertices) {
        buffer += 'v';
        for (int i = 0; i < 3; ++i) {
            buffer += ' ';
            const auto result = std::to_chars(number, number + sizeof number, v[i]);
            buffer.append(number, result.ptr);
        }
        buffer += '\n';
        if (buffer.size() > (1 << 20) - 256) flush();
    }
    for (const Tri& t : mesh.triangles) {
        buffer += 'f';
        for (std::int32_t i : t) {
            buffer += ' ';
            const auto result = std::to_chars(number, number + sizeof number, static_cast<std::int64_t>(i) + 1);
            buffer.append(number, result.ptr);
        }
        buffer += '\n';
        if (buffer.size() > (1 << 20) - 256) flush();
    }
    flush();
}

}  // namespace jawmesh::detail
