// Format dispatch by extension plus the checks every reader shares. The formats themselves live in
// io/StlFormat.cpp, io/ObjFormat.cpp, io/PlyFormat.cpp and io/OffFormat.cpp.
#include "io/MeshIO.h"

#include "io/AtomicFile.h"
#include "io/Error.h"
#include "io/detail/MeshFormats.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

namespace jawmesh {
namespace {

std::string readWholeFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        throw Error(path, "is not a regular file");
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) throw Error(path, std::string("cannot open file: ") + std::strerror(errno));
    if (std::fseek(file.get(), 0, SEEK_END) != 0) throw Error(path, "cannot seek (not a regular file?)");
    const long size = std::ftell(file.get());
    if (size < 0) throw Error(path, "cannot read file size (not a regular file?)");
    std::fseek(file.get(), 0, SEEK_SET);
    std::string data;
    data.resize(static_cast<std::size_t>(size));
    if (size > 0 && std::fread(data.data(), 1, data.size(), file.get()) != data.size())
        throw Error(path, "read failed");
    return data;
}

}  // namespace

std::string surfaceExtension(const std::string& path) {
    const auto slash = path.find_last_of("/\\");
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

bool isSurfaceExtension(const std::string& extension) {
    return extension == "stl" || extension == "obj" || extension == "ply" || extension == "off";
}

SurfaceMesh readSurface(const std::string& path) {
    const std::string ext = surfaceExtension(path);
    if (!isSurfaceExtension(ext))
        throw Error(path, "unsupported surface format '." + ext + "' (expected .stl, .obj, .ply or .off)");
    return readSurfaceFromMemory(readWholeFile(path), path);
}

SurfaceMesh readSurfaceFromMemory(const std::string& data, const std::string& name) {
    const std::string ext = surfaceExtension(name);
    if (!isSurfaceExtension(ext))
        throw Error(name, "unsupported surface format '." + ext + "' (expected .stl, .obj, .ply or .off)");
    if (data.empty()) throw Error(name, "file is empty");
    if (ext == "stl") return detail::readStl(name, data);
    if (ext == "obj") return detail::readObj(name, data);
    if (ext == "ply") return detail::readPly(name, data);
    return detail::readOff(name, data);
}

void writeSurface(const SurfaceMesh& mesh, const std::string& path) {
    const std::string ext = surfaceExtension(path);
    for (const Tri& t : mesh.triangles)
        for (std::int32_t v : t)
            if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size())
                throw Error(path, "cannot write a mesh whose triangles index missing vertices");
    if (ext == "stl") {
        writeFileAtomically(path, [&](std::ostream& out) { detail::writeBinaryStl(mesh, out); });
    } else if (ext == "ply") {
        writeFileAtomically(path, [&](std::ostream& out) { detail::writeBinaryPly(mesh, out); });
    } else if (ext == "obj") {
        writeFileAtomically(path, [&](std::ostream& out) { detail::writeObj(mesh, out); });
    } else {
        throw Error(path, "cannot write surface format '." + ext + "' (expected .stl, .ply or .obj)");
    }
}

namespace detail {

void validateMesh(const std::string& path, const SurfaceMesh& mesh) {
    if (mesh.triangles.empty()) throw Error(path, "file holds no triangles");
    if (mesh.vertices.size() > kMaxElements || mesh.triangles.size() > kMaxElements)
        throw Error(path, "more than 2^31-1 vertices or triangles");
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
        if (!mesh.vertices[i].allFinite())
            throw Error(path, "vertex " + std::to_string(i) + " has a NaN or infinite coordinate");
    const auto n = static_cast<std::int64_t>(mesh.vertices.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (std::int32_t v : mesh.triangles[t])
            if (v < 0 || v >= n)
                throw Error(path, "triangle " + std::to_string(t) + " uses vertex index " + std::to_string(v) +
                                      " outside 0.." + std::to_string(n - 1));
}

void requireText(const std::string& path, std::string_view data, const char* format) {
    if (data.find('\0') != std::string_view::npos)
        throw Error(path, std::string("holds binary data (NUL bytes); not a text ") + format + " file");
}

}  // namespace detail
}  // namespace jawmesh
