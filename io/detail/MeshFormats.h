// Private to io/: one reader/writer pair per surface format (io/StlFormat.cpp, io/ObjFormat.cpp,
// io/PlyFormat.cpp, io/OffFormat.cpp), the vertex welding they share, and the small text-parsing
// helpers every text format uses. io/MeshIO.cpp dispatches to these by extension.
// Every reader takes the file path (for messages only) and the whole file content; it throws
// Error(path, reason) for malformed data and never allocates more than the file can justify.
#pragma once

#include "io/Error.h"
#include "io/SurfaceMesh.h"

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>

namespace jawmesh::detail {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "binary mesh formats assume a little-endian host");

/// Welds a triangle soup given as float corners: triangle t's corners are 3 consecutive float
/// triples (36 bytes) starting at first + t * triangleStride (unaligned reads are fine). Corners
/// with bit-identical positions (+0 and -0 equal) share one vertex; vertices are numbered in order
/// of first use, so the result does not depend on the thread count.
/// Throws Error(path, ...) for NaN/Inf coordinates or more than 2^31-1 corners.
/// Cost: O(corners), parallel (TBB), about 4 streaming passes over 16 bytes per corner.
SurfaceMesh weldFloatCorners(const std::string& path, const char* first, std::size_t triangleCount,
                             std::size_t triangleStride);

SurfaceMesh readStl(const std::string& path, std::string_view data);   ///< binary or ASCII, welded
SurfaceMesh readObj(const std::string& path, std::string_view data);
SurfaceMesh readPly(const std::string& path, std::string_view data);   ///< ascii, binary_little_endian
SurfaceMesh readOff(const std::string& path, std::string_view data);

void writeBinaryStl(const SurfaceMesh& mesh, std::ostream& out);
void writeBinaryPly(const SurfaceMesh& mesh, std::ostream& out);   ///< double x,y,z; int indices
void writeObj(const SurfaceMesh& mesh, std::ostream& out);         ///< shortest round-trip decimals

/// Throws Error(path, ...) unless the mesh has a triangle, every coordinate is finite and every
/// index is in [0, vertices). Readers call it last. Cost: O(vertices + triangles).
void validateMesh(const std::string& path, const SurfaceMesh& mesh);

/// Throws Error(path, "... binary data ...") when a text format holds NUL bytes (binary noise).
void requireText(const std::string& path, std::string_view data, const char* format);

/// Splits text into lines ('\n', '\r\n' or '\r'); counts lines from 1 for messages.
class LineReader {
public:
    explicit LineReader(std::string_view data) : data_(data) {}
    /// Next line without its terminator; false at the end.
    bool next(std::string_view& line) {
        if (pos_ >= data_.size()) return false;
        std::size_t end = pos_;
        while (end < data_.size() && data_[end] != '\n' && data_[end] != '\r') ++end;
        line = data_.substr(pos_, end - pos_);
        pos_ = end;
        if (pos_ < data_.size() && data_[pos_] == '\r') {
            ++pos_;
            if (pos_ < data_.size() && data_[pos_] == '\n') ++pos_;
        } else if (pos_ < data_.size() && data_[pos_] == '\n') {
            ++pos_;
        }
        ++lineNumber_;
        return true;
    }
    std::size_t lineNumber() const { return lineNumber_; }
    std::size_t offset() const { return pos_; }
    std::size_t remaining() const { return data_.size() - pos_; }

private:
    std::string_view data_;
    std::size_t pos_ = 0;
    std::size_t lineNumber_ = 0;
};

/// Whitespace-separated tokens of a string_view.
class Tokens {
public:
    explicit Tokens(std::string_view text) : text_(text) {}
    /// Next token; empty at the end.
    std::string_view next() {
        while (pos_ < text_.size() && isSpace(text_[pos_])) ++pos_;
        const std::size_t start = pos_;
        while (pos_ < text_.size() && !isSpace(text_[pos_])) ++pos_;
        return text_.substr(start, pos_ - start);
    }
    bool atEnd() {
        while (pos_ < text_.size() && isSpace(text_[pos_])) ++pos_;
        return pos_ >= text_.size();
    }
    std::size_t remaining() const { return text_.size() - pos_; }
    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

private:
    std::string_view text_;
    std::size_t pos_ = 0;
};

/// Parses a whole token as a finite double ("+1.5", "1e-3"); false otherwise (NaN/Inf included).
inline bool parseDouble(std::string_view token, double& value) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    return ec == std::errc() && end == token.data() + token.size() && std::isfinite(value);
}

/// Parses a whole token as a signed 64-bit integer; false otherwise.
inline bool parseInt(std::string_view token, std::int64_t& value) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    return ec == std::errc() && end == token.data() + token.size();
}

/// A token quoted for an error message, shortened so binary noise cannot flood it.
inline std::string quoted(std::string_view token) {
    std::string s;
    for (char c : token.substr(0, 32)) s += (c >= 32 && c < 127) ? c : '?';
    return "'" + s + (token.size() > 32 ? "...'" : "'");
}

/// Largest vertex or triangle count a SurfaceMesh can index (int32 indices).
constexpr std::uint64_t kMaxElements = 0x7fffffffull;

}  // namespace jawmesh::detail
