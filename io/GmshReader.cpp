// Implements io/GmshReader.h; what it computes, its rules and its contract are documented there.
#include "io/GmshReader.h"

#include "io/Error.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

namespace jawmesh {
namespace {

/// Nodes per element for the MSH element types a jaw mesh file may contain.
int nodesOfType(int type) {
    switch (type) {
    case 15: return 1;   // point
    case 1: return 2;    // line
    case 2: return 3;    // triangle
    case 3: return 4;    // quadrangle
    case 4: return 4;    // tetrahedron
    case 5: return 8;    // hexahedron
    case 6: return 6;    // prism
    case 7: return 5;    // pyramid
    case 8: return 3;    // line3
    case 9: return 6;    // triangle6
    case 10: return 9;   // quadrangle9
    case 11: return 10;  // tetrahedron10
    case 16: return 8;   // quadrangle8
    case 17: return 20;  // hexahedron20
    case 18: return 15;  // prism15
    case 19: return 13;  // pyramid13
    default: return -1;
    }
}

class Cursor {
public:
    Cursor(std::string data, std::string path) : d_(std::move(data)), path_(std::move(path)) {}
    [[noreturn]] void fail(const std::string& reason) const { throw Error(path_, reason); }
    bool atEnd() {
        skipSpace();
        return p_ >= d_.size();
    }
    std::string line() {
        if (p_ >= d_.size()) fail("unexpected end of file");
        std::size_t e = d_.find('\n', p_);
        if (e == std::string::npos) e = d_.size();
        std::string s = d_.substr(p_, e - p_);
        p_ = std::min(d_.size(), e + 1);
        while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t')) s.pop_back();
        return s;
    }
    void skipSpace() {
        while (p_ < d_.size() && std::isspace(static_cast<unsigned char>(d_[p_]))) ++p_;
    }
    std::string token() {
        skipSpace();
        if (p_ >= d_.size()) fail("unexpected end of file");
        const std::size_t b = p_;
        while (p_ < d_.size() && !std::isspace(static_cast<unsigned char>(d_[p_]))) ++p_;
        return d_.substr(b, p_ - b);
    }
    template <class T>
    T raw() {
        if (p_ + sizeof(T) > d_.size()) fail("truncated binary data");
        T v;
        std::memcpy(&v, d_.data() + p_, sizeof(T));
        p_ += sizeof(T);
        return v;
    }
    void setBinary(bool b) { binary_ = b; }
    std::uint64_t size() {
        if (binary_) return raw<std::uint64_t>();
        const std::string t = token();
        char* end = nullptr;
        const unsigned long long v = std::strtoull(t.c_str(), &end, 10);
        if (*end || t.empty() || t[0] == '-') fail("expected a non-negative integer, found '" + t + "'");
        return v;
    }
    std::int32_t integer() {
        if (binary_) return raw<std::int32_t>();
        const std::string t = token();
        char* end = nullptr;
        const long v = std::strtol(t.c_str(), &end, 10);
        if (*end || t.empty()) fail("expected an integer, found '" + t + "'");
        return static_cast<std::int32_t>(v);
    }
    double real() {
        double v;
        if (binary_) {
            v = raw<double>();
        } else {
            const std::string t = token();
            char* end = nullptr;
            v = std::strtod(t.c_str(), &end);
            if (*end || t.empty()) fail("expected a number, found '" + t + "'");
        }
        if (!std::isfinite(v)) fail("non-finite coordinate");
        return v;
    }
    /// Skips to after the line "$End<name>".
    void endSection(const std::string& name) {
        const std::string marker = "$End" + name;
        for (;;) {
            skipSpace();
            if (p_ >= d_.size()) fail("missing " + marker);
            if (line() == marker) return;
            if (binary_ || name == "MeshFormat" || name == "Entities" || name == "Nodes" || name == "Elements")
                fail("unexpected data before " + marker);
        }
    }
    /// Unknown sections: skip lines up to the end marker (their binary data may contain anything,
    /// so search for the marker text).
    void skipSection(const std::string& name) {
        const std::string marker = "\n$End" + name;
        const std::size_t e = d_.find(marker, p_ == 0 ? 0 : p_ - 1);
        if (e == std::string::npos) fail("missing $End" + name);
        p_ = e + 1;
        line();
    }

private:
    std::string d_;
    std::string path_;
    std::size_t p_ = 0;
    bool binary_ = false;
};

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "cannot open for reading");
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw Error(path, "read failed");
    return ss.str();
}

using GmshNodes = std::vector<std::pair<std::uint64_t, Vec3>>;  ///< (tag, position mm)

/// A volume element as read: its tag, first four node tags and the label of its entity.
struct GmshElement {
    std::uint64_t tag;
    std::array<std::uint64_t, 4> corners;
    Label label;
};

/// $MeshFormat: MSH 4.1 with 8-byte data, ASCII or binary (then the cursor switches to binary).
void readFormat(Cursor& c) {
    std::istringstream ls(c.line());
    std::string version;
    int fileType = -1, dataSize = -1;
    ls >> version >> fileType >> dataSize;
    if (version.rfind("4.1", 0) != 0) c.fail("MSH version " + version + " is not supported (write MSH 4.1, e.g. gmsh -format msh41)");
    if (dataSize != 8) c.fail("MSH data size " + std::to_string(dataSize) + " is not supported (expected 8)");
    if (fileType == 1) {
        c.setBinary(true);
        if (c.raw<std::int32_t>() != 1) c.fail("binary MSH written with another byte order");
    } else if (fileType != 0) {
        c.fail("unknown MSH file type " + std::to_string(fileType));
    }
}

/// $Entities: the one physical tag (the region label) of every volume entity.
void readEntities(Cursor& c, std::map<std::int32_t, Label>& physicalOfVolume) {
    std::uint64_t counts[4];
    for (auto& n : counts) n = c.size();
    for (int dim = 0; dim < 4; ++dim) {
        for (std::uint64_t i = 0; i < counts[dim]; ++i) {
            const std::int32_t tag = c.integer();
            for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) c.real();
            const std::uint64_t nPhys = c.size();
            if (nPhys > 1000000) c.fail("implausible physical tag count");
            std::vector<std::int32_t> phys;
            for (std::uint64_t k = 0; k < nPhys; ++k) phys.push_back(c.integer());
            if (dim > 0) {
                const std::uint64_t nBound = c.size();
                if (nBound > 100000000) c.fail("implausible bounding entity count");
                for (std::uint64_t k = 0; k < nBound; ++k) c.integer();
            }
            if (dim == 3) {
                if (phys.size() != 1)
                    c.fail("volume entity " + std::to_string(tag) + " has " + std::to_string(phys.size()) +
                           " physical tags (expected exactly one: the region label)");
                physicalOfVolume[tag] = phys[0];
            }
        }
    }
}

void readNodes(Cursor& c, GmshNodes& nodes) {
    const std::uint64_t blocks = c.size(), total = c.size();
    c.size(), c.size();
    if (total > (1ull << 31)) c.fail("too many nodes");
    nodes.reserve(total);
    for (std::uint64_t b = 0; b < blocks; ++b) {
        const std::int32_t dim = c.integer();
        c.integer();
        const std::int32_t parametric = c.integer();
        const std::uint64_t n = c.size();
        if (n > total) c.fail("a node block is larger than the node count");
        const std::size_t first = nodes.size();
        for (std::uint64_t i = 0; i < n; ++i) nodes.push_back({c.size(), Vec3::Zero()});
        const int params = parametric ? std::clamp(dim, 0, 3) : 0;
        for (std::uint64_t i = 0; i < n; ++i) {
            Vec3& p = nodes[first + i].second;
            p.x() = c.real(), p.y() = c.real(), p.z() = c.real();
            for (int k = 0; k < params; ++k) c.real();
        }
    }
    if (nodes.size() != total) c.fail("node blocks hold " + std::to_string(nodes.size()) + " nodes, header says " + std::to_string(total));
}

/// $Elements: the tetrahedra (linear or quadratic, corners kept) with their entity's label; lower
/// dimensional elements are read past.
void readElements(Cursor& c, const std::map<std::int32_t, Label>& physicalOfVolume, std::vector<GmshElement>& elements) {
    const std::uint64_t blocks = c.size(), total = c.size();
    c.size(), c.size();
    for (std::uint64_t b = 0; b < blocks; ++b) {
        const std::int32_t dim = c.integer(), entity = c.integer(), type = c.integer();
        const std::uint64_t n = c.size();
        if (n > total) c.fail("an element block is larger than the element count");
        const int nn = nodesOfType(type);
        if (nn < 0) c.fail("unsupported element type " + std::to_string(type));
        if (dim == 3 && type != 4 && type != 11)
            c.fail("volume elements of type " + std::to_string(type) + " (only tetrahedra, types 4 and 11, are supported)");
        Label label = 0;
        if (dim == 3) {
            const auto it = physicalOfVolume.find(entity);
            if (it == physicalOfVolume.end()) c.fail("volume entity " + std::to_string(entity) + " is not in $Entities");
            label = it->second;
        }
        for (std::uint64_t i = 0; i < n; ++i) {
            GmshElement e{c.size(), {}, label};
            for (int k = 0; k < nn; ++k) {
                const std::uint64_t v = c.size();
                if (k < 4) e.corners[static_cast<std::size_t>(k)] = v;
            }
            if (dim == 3) elements.push_back(e);
        }
    }
}

/// The mesh in tag order: nodes renumbered from 0, every element's nodes defined once.
TetMesh assembleMesh(Cursor& c, GmshNodes& nodes, std::vector<GmshElement>& elements) {
    TetMesh mesh;
    std::sort(nodes.begin(), nodes.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::unordered_map<std::uint64_t, std::int32_t> index;
    index.reserve(nodes.size());
    mesh.nodes.reserve(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (i > 0 && nodes[i].first == nodes[i - 1].first) c.fail("node tag " + std::to_string(nodes[i].first) + " defined twice");
        index[nodes[i].first] = static_cast<std::int32_t>(i);
        mesh.nodes.push_back(nodes[i].second);
    }
    std::sort(elements.begin(), elements.end(), [](const GmshElement& a, const GmshElement& b) { return a.tag < b.tag; });
    mesh.tets.reserve(elements.size());
    mesh.labels.reserve(elements.size());
    for (const GmshElement& e : elements) {
        Tet t;
        for (std::size_t k = 0; k < 4; ++k) {
            const auto it = index.find(e.corners[k]);
            if (it == index.end()) c.fail("element " + std::to_string(e.tag) + " uses undefined node " + std::to_string(e.corners[k]));
            t[k] = it->second;
        }
        mesh.tets.push_back(t);
        mesh.labels.push_back(e.label);
    }
    return mesh;
}

}  // namespace

TetMesh readGmsh(const std::string& path) {
    Cursor c(readAll(path), path);
    bool sawFormat = false, sawNodes = false, sawElements = false;
    std::map<std::int32_t, Label> physicalOfVolume;
    GmshNodes nodes;
    std::vector<GmshElement> elements;
    while (!c.atEnd()) {
        const std::string header = c.line();
        if (header.empty() || header[0] != '$') c.fail("expected a section, found '" + header.substr(0, 40) + "'");
        const std::string name = header.substr(1);
        if (name == "MeshFormat") readFormat(c), sawFormat = true;
        else if (!sawFormat) c.fail("the file does not start with $MeshFormat (not a Gmsh MSH file)");
        else if (name == "Entities") readEntities(c, physicalOfVolume);
        else if (name == "Nodes") readNodes(c, nodes), sawNodes = true;
        else if (name == "Elements") readElements(c, physicalOfVolume, elements), sawElements = true;
        else {
            c.skipSection(name);
            continue;
        }
        c.endSection(name);
    }
    if (!sawFormat) c.fail("empty file");
    if (!sawNodes) c.fail("no $Nodes section");
    if (!sawElements) c.fail("no $Elements section");
    return assembleMesh(c, nodes, elements);
}

}  // namespace jawmesh
