// PLY (Stanford polygon format), ascii and binary_little_endian: the "vertex" element's x, y, z
// (any scalar type, among other properties in any order) and the "face" element's
// vertex_indices / vertex_index list (any count and index types); other elements and properties
// are skipped. binary_big_endian is refused with a message saying so.
#include "io/detail/MeshFormats.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

namespace jawmesh::detail {
namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool plyTypeFromName(std::string_view name, PlyType& type) {
    static const struct { const char* a; const char* b; PlyType t; } names[] = {
        {"char", "int8", PlyType::Int8},      {"uchar", "uint8", PlyType::UInt8},    {"short", "int16", PlyType::Int16},
        {"ushort", "uint16", PlyType::UInt16}, {"int", "int32", PlyType::Int32},     {"uint", "uint32", PlyType::UInt32},
        {"float", "float32", PlyType::Float32}, {"double", "float64", PlyType::Float64}};
    for (const auto& n : names)
        if (name == n.a || name == n.b) {
            type = n.t;
            return true;
        }
    return false;
}

std::size_t plySize(PlyType t) {
    switch (t) {
        case PlyType::Int8: case PlyType::UInt8: return 1;
        case PlyType::Int16: case PlyType::UInt16: return 2;
        case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
        case PlyType::Float64: return 8;
    }
    return 8;
}

bool isIntegral(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32;   ///< item type for lists
    bool isList = false;
    PlyType countType = PlyType::UInt8;
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

/// Reads the body value by value, in ascii or binary little-endian, with bounds checks.
class PlyBody {
public:
    PlyBody(const std::string& path, std::string_view body, bool ascii)
        : path_(path), body_(body), ascii_(ascii), tokens_(body) {}

    std::size_t remainingBytes() const { return ascii_ ? tokens_.remaining() : body_.size() - pos_; }
    bool ascii() const { return ascii_; }

    /// Sets the element messages talk about ("face 12").
    void at(const std::string& element, std::uint64_t index) {
        element_ = &element;
        index_ = index;
    }
    std::string where() const { return element_ ? *element_ + " " + std::to_string(index_) : std::string("body"); }

    /// Reads one value of type t as a double.
    double number(PlyType t) {
        if (ascii_) {
            const std::string_view token = tokens_.next();
            if (token.empty()) truncated();
            if (isIntegral(t)) {
                std::int64_t v = 0;
                if (!parseInt(token, v)) throw Error(path_, where() + ": " + quoted(token) + " is not an integer");
                return static_cast<double>(v);
            }
            double v = 0;
            if (!parseDouble(token, v)) throw Error(path_, where() + ": " + quoted(token) + " is not a finite number");
            return v;
        }
        const std::size_t size = plySize(t);
        if (body_.size() - pos_ < size) truncated();
        const char* p = body_.data() + pos_;
        pos_ += size;
        switch (t) {
            case PlyType::Int8: { std::int8_t v; std::memcpy(&v, p, 1); return v; }
            case PlyType::UInt8: { std::uint8_t v; std::memcpy(&v, p, 1); return v; }
            case PlyType::Int16: { std::int16_t v; std::memcpy(&v, p, 2); return v; }
            case PlyType::UInt16: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
            case PlyType::Int32: { std::int32_t v; std::memcpy(&v, p, 4); return v; }
            case PlyType::UInt32: { std::uint32_t v; std::memcpy(&v, p, 4); return v; }
            case PlyType::Float32: { float v; std::memcpy(&v, p, 4); return v; }
            case PlyType::Float64: { double v; std::memcpy(&v, p, 8); return v; }
        }
        return 0;
    }

    /// Skips one value (no parsing in ascii, so odd values in ignored properties do not matter).
    void skip(PlyType t) {
        if (ascii_) {
            if (tokens_.next().empty()) truncated();
            return;
        }
        if (body_.size() - pos_ < plySize(t)) truncated();
        pos_ += plySize(t);
    }

    [[noreturn]] void truncated() const {
        throw Error(path_, "file ends while reading " + where() + " (truncated)");
    }

private:
    const std::string& path_;
    std::string_view body_;
    bool ascii_;
    Tokens tokens_;
    std::size_t pos_ = 0;
    const std::string* element_ = nullptr;
    std::uint64_t index_ = 0;
};

/// Reads a list length; refuses lengths the rest of the file cannot hold.
std::size_t listLength(PlyBody& body, const PlyProperty& p, const std::string& path) {
    const double n = body.number(p.countType);
    if (n < 0 || n != static_cast<double>(static_cast<std::uint64_t>(n)))
        throw Error(path, body.where() + ": list length " + std::to_string(n) + " is not a non-negative integer");
    const std::size_t itemBytes = body.ascii() ? 1 : plySize(p.type);
    if (n * static_cast<double>(itemBytes) > static_cast<double>(body.remainingBytes()))
        throw Error(path, body.where() + ": list of " + std::to_string(static_cast<std::uint64_t>(n)) +
                              " items is longer than the rest of the file (truncated or corrupt)");
    return static_cast<std::size_t>(n);
}

/// A PLY header: its elements in file order, the format and where the body starts.
struct PlyHeader {
    std::vector<PlyElement> elements;
    bool ascii = false;
    std::size_t bodyOffset = 0;
};

/// One 'property' line (after the keyword) of the last element.
PlyProperty plyProperty(Tokens& tokens, const std::function<void(const std::string&)>& fail) {
    PlyProperty p;
    std::string_view typeName = tokens.next();
    if (typeName == "list") {
        p.isList = true;
        if (!plyTypeFromName(tokens.next(), p.countType) || !isIntegral(p.countType)) fail("list count type must be an integer type");
        typeName = tokens.next();
    }
    if (!plyTypeFromName(typeName, p.type)) fail("unknown property type " + quoted(typeName));
    p.name = std::string(tokens.next());
    if (p.name.empty()) fail("property without a name");
    return p;
}

PlyHeader readPlyHeader(const std::string& path, std::string_view data) {
    LineReader lines(data);
    std::string_view line;
    if (!lines.next(line) || line != "ply") throw Error(path, "not a PLY file (the first line is not 'ply')");
    const std::function<void(const std::string&)> fail = [&](const std::string& what) {
        throw Error(path, "header line " + std::to_string(lines.lineNumber()) + ": " + what);
    };
    PlyHeader h;
    bool sawFormat = false, sawEnd = false;
    while (lines.next(line)) {
        if (line.find('\0') != std::string_view::npos) fail("binary data inside the header");
        Tokens tokens(line);
        const std::string_view keyword = tokens.next();
        if (keyword == "end_header") {
            sawEnd = true;
            break;
        }
        if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "format") {
            const std::string_view format = tokens.next();
            if (format == "ascii") h.ascii = true;
            else if (format == "binary_little_endian") h.ascii = false;
            else if (format == "binary_big_endian") fail("binary_big_endian PLY is not supported; re-export as binary_little_endian or ascii");
            else fail("unknown PLY format " + quoted(format));
            sawFormat = true;
        } else if (keyword == "element") {
            PlyElement e;
            e.name = std::string(tokens.next());
            std::int64_t count = 0;
            const std::string_view countToken = tokens.next();
            if (e.name.empty() || !parseInt(countToken, count) || count < 0) fail("expected 'element <name> <count>'");
            e.count = static_cast<std::uint64_t>(count);
            h.elements.push_back(std::move(e));
        } else if (keyword == "property") {
            if (h.elements.empty()) fail("property before any element");
            h.elements.back().properties.push_back(plyProperty(tokens, fail));
        } else {
            fail("unexpected " + quoted(keyword));
        }
    }
    if (!sawEnd) throw Error(path, "PLY header has no 'end_header' (truncated or not a PLY file)");
    if (!sawFormat) throw Error(path, "PLY header has no 'format' line");
    h.bodyOffset = lines.offset();
    return h;
}

/// Where an element's x, y, z (vertex) and vertex-index list (face) are among its properties.
struct PlyLayout {
    bool isVertex = false, isFace = false;
    int xyzIndex[3] = {-1, -1, -1};
    int indicesIndex = -1;
};

PlyLayout plyLayout(const std::string& path, const PlyElement& e) {
    PlyLayout l;
    l.isVertex = e.name == "vertex";
    l.isFace = e.name == "face";
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const PlyProperty& p = e.properties[i];
        if (l.isVertex && !p.isList) {
            if (p.name == "x") l.xyzIndex[0] = static_cast<int>(i);
            if (p.name == "y") l.xyzIndex[1] = static_cast<int>(i);
            if (p.name == "z") l.xyzIndex[2] = static_cast<int>(i);
        }
        if (l.isFace && p.isList && (p.name == "vertex_indices" || p.name == "vertex_index")) {
            if (!isIntegral(p.type)) throw Error(path, "face property '" + p.name + "' must hold integers");
            l.indicesIndex = static_cast<int>(i);
        }
    }
    return l;
}

/// A face's polygon, fanned into triangles appended to the mesh.
void readPlyPolygon(const std::string& path, PlyBody& body, const PlyProperty& p, std::size_t length, SurfaceMesh& mesh,
                    std::vector<std::int32_t>& polygon) {
    if (length < 3) throw Error(path, body.where() + " has " + std::to_string(length) + " corners (at least 3 needed)");
    polygon.clear();
    for (std::size_t j = 0; j < length; ++j) {
        const double v = body.number(p.type);
        if (v < 0 || v >= static_cast<double>(kMaxElements))
            throw Error(path, body.where() + " uses vertex index " + std::to_string(static_cast<std::int64_t>(v)) + " (out of range)");
        polygon.push_back(static_cast<std::int32_t>(v));
    }
    for (std::size_t j = 1; j + 1 < polygon.size(); ++j) {
        if (mesh.triangles.size() >= kMaxElements) throw Error(path, "more than 2^31-1 triangles");
        mesh.triangles.push_back({polygon[0], polygon[j], polygon[j + 1]});
    }
}

/// Element n's properties: coordinates of a vertex, the polygon of a face, the rest skipped.
void readPlyRecord(const std::string& path, PlyBody& body, const PlyElement& e, const PlyLayout& l, std::uint64_t n,
                   SurfaceMesh& mesh, std::vector<std::int32_t>& polygon) {
    body.at(e.name, n);
    for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const PlyProperty& p = e.properties[i];
        const int pi = static_cast<int>(i);
        if (p.isList) {
            const std::size_t length = listLength(body, p, path);
            if (pi == l.indicesIndex) readPlyPolygon(path, body, p, length, mesh, polygon);
            else
                for (std::size_t j = 0; j < length; ++j) body.skip(p.type);
        } else if (l.isVertex && (pi == l.xyzIndex[0] || pi == l.xyzIndex[1] || pi == l.xyzIndex[2])) {
            const int axis = pi == l.xyzIndex[0] ? 0 : pi == l.xyzIndex[1] ? 1 : 2;
            const double v = body.number(p.type);
            if (!std::isfinite(v)) throw Error(path, body.where() + " has a NaN or infinite coordinate");
            mesh.vertices[static_cast<std::size_t>(n)][axis] = v;
        } else {
            body.skip(p.type);
        }
    }
}

}  // namespace

SurfaceMesh readPly(const std::string& path, std::string_view data) {
    const PlyHeader header = readPlyHeader(path, data);
    const bool ascii = header.ascii;
    PlyBody body(path, data.substr(header.bodyOffset), ascii);
    SurfaceMesh mesh;
    bool sawVertices = false, sawFaces = false;
    std::vector<std::int32_t> polygon;
    for (const PlyElement& e : header.elements) {
        // Every element needs at least one byte (ascii: one character) per property.
        std::size_t minBytes = 0;
        for (const PlyProperty& p : e.properties) minBytes += ascii ? 1 : (p.isList ? plySize(p.countType) : plySize(p.type));
        if (static_cast<double>(e.count) * static_cast<double>(minBytes) > static_cast<double>(body.remainingBytes()))
            throw Error(path, "header promises " + std::to_string(e.count) + " '" + e.name +
                                  "' elements, more than the rest of the file can hold (truncated or corrupt)");
        const PlyLayout layout = plyLayout(path, e);
        if (layout.isVertex) {
            if (layout.xyzIndex[0] < 0 || layout.xyzIndex[1] < 0 || layout.xyzIndex[2] < 0)
                throw Error(path, "vertex element lacks scalar x, y, z properties");
            if (e.count > kMaxElements || sawVertices) throw Error(path, "too many vertices or a second vertex element");
            mesh.vertices.resize(static_cast<std::size_t>(e.count));
            sawVertices = true;
        }
        if (layout.isFace) {
            if (layout.indicesIndex < 0) throw Error(path, "face element lacks a vertex_indices list");
            if (sawFaces) throw Error(path, "second face element");
            mesh.triangles.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(e.count, kMaxElements)));
            sawFaces = true;
        }
        // An element without properties holds no bytes whatever its count: nothing to read (a
        // count of 10^18 would otherwise be a loop of 10^18 empty iterations).
        if (e.properties.empty()) continue;
        for (std::uint64_t n = 0; n < e.count; ++n) readPlyRecord(path, body, e, layout, n, mesh, polygon);
    }
    if (!sawVertices) throw Error(path, "PLY file has no vertex element");
    if (!sawFaces) throw Error(path, "PLY file has no face element (a point cloud is not a surface)");
    validateMesh(path, mesh);
    return mesh;
}

void writeBinaryPly(const SurfaceMesh& mesh, std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\ncomment jawmesh surface, millimetres\n"
        << "element vertex " << mesh.vertices.size() << "\nproperty double x\nproperty double y\nproperty double z\n"
        << "element face " << mesh.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    std::vector<char> buffer;
    buffer.reserve(1 << 20);
    auto flushIfFull = [&] {
        if (buffer.size() > (1 << 20) - 64) {
            out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
            buffer.clear();
        }
    };
    for (const Vec3& v : mesh.vertices) {
        const double xyz[3] = {v.x(), v.y(), v.z()};
        const char* p = reinterpret_cast<const char*>(xyz);
        buffer.insert(buffer.end(), p, p + sizeof xyz);
        flushIfFull();
    }
    for (const Tri& t : mesh.triangles) {
        buffer.push_back(3);
        const char* p = reinterpret_cast<const char*>(t.data());
        buffer.insert(buffer.end(), p, p + 12);
        flushIfFull();
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

}  // namespace jawmesh::detail
