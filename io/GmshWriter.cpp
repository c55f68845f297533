// Implements io/GmshWriter.h; what it computes, its rules and its contract are documented there.
#include "io/GmshWriter.h"

#include "io/AtomicFile.h"
#include "io/NumberText.h"
#include "io/Error.h"

#include <algorithm>
#include <functional>
#include <map>
#include <ostream>

namespace jawmesh {
namespace {

/// Writes numbers as ASCII tokens (space-separated, one record per line) or raw little-endian.
class MshOut {
public:
    MshOut(std::ostream& out, bool binary) : out_(out), binary_(binary) {}
    void size(std::uint64_t v) {
        if (binary_) raw(v);
        else token(std::to_string(v));
    }
    void integer(std::int32_t v) {
        if (binary_) raw(v);
        else token(std::to_string(v));
    }
    void real(double v) {
        if (binary_) {
            raw(v);
        } else {
            token(numberText(v));  // shortest exact round trip
        }
    }
    void endRecord() {
        if (!binary_) out_ << '\n';
        first_ = true;
    }
    /// A text line (section names), also in binary files.
    void line(const std::string& s) {
        first_ = true;
        out_ << s << '\n';
    }
    /// Binary data blocks are followed by a newline before the $End line.
    void endBinaryBlock() {
        if (binary_) out_ << '\n';
    }

private:
    template <class T>
    void raw(T v) {
        first_ = false;
        out_.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
    void token(const std::string& s) {
        if (!first_) out_ << ' ';
        out_ << s;
        first_ = false;
    }
    std::ostream& out_;
    bool binary_;
    bool first_ = true;
};

struct Block {
    Label label;
    int type;  // 4 or 11
    std::vector<std::size_t> tets;
};

void writeMsh(const std::vector<Vec3>& nodes, std::size_t tetCount, const std::vector<Label>& labels,
              const std::function<int(std::size_t)>& nodeCount, const std::function<std::int32_t(std::size_t, int)>& node,
              const std::string& path, const GmshWriteOptions& options) {
    if (labels.size() != tetCount)
        throw Error(path, std::to_string(labels.size()) + " labels for " + std::to_string(tetCount) + " tets");
    std::map<Label, std::string> names;
    for (Label l : labels) {
        if (names.count(l)) continue;
        if (l <= 0) throw Error(path, "tet label " + std::to_string(l) + " cannot be a Gmsh physical tag (must be > 0)");
        names[l] = labelName(l);  // throws for unknown labels
    }
    // Each node belongs to the entity of the lowest label among its tets (Gmsh wants every node in
    // exactly one entity); bounding boxes per entity.
    std::vector<Label> nodeEntity(nodes.size(), 0);
    std::map<Label, BBox> boxes;
    std::map<std::pair<Label, int>, Block> blocks;
    for (std::size_t t = 0; t < tetCount; ++t) {
        const int nn = nodeCount(t);
        const int type = nn == 10 ? 11 : 4;
        auto& b = blocks[{labels[t], type}];
        b.label = labels[t];
        b.type = type;
        b.tets.push_back(t);
        for (int k = 0; k < nn; ++k) {
            const std::int32_t v = node(t, k);
            if (v < 0 || static_cast<std::size_t>(v) >= nodes.size())
                throw Error(path, "tet " + std::to_string(t) + " has a node index out of range");
            Label& e = nodeEntity[static_cast<std::size_t>(v)];
            if (e == 0 || labels[t] < e) e = labels[t];
            boxes[labels[t]].extend(nodes[static_cast<std::size_t>(v)]);
        }
    }
    std::map<Label, std::vector<std::size_t>> nodesOf;
    std::size_t usedNodes = 0, minTag = 0, maxTag = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (nodeEntity[i] == 0) continue;
        nodesOf[nodeEntity[i]].push_back(i);
        if (usedNodes++ == 0) minTag = i + 1;
        maxTag = i + 1;
    }

    writeFileAtomically(path, [&](std::ostream& os) {
        MshOut out(os, options.binary);
        out.line("$MeshFormat");
        out.line(options.binary ? "4.1 1 8" : "4.1 0 8");
        if (options.binary) {
            const std::int32_t one = 1;
            os.write(reinterpret_cast<const char*>(&one), sizeof one);
            os << '\n';
        }
        out.line("$EndMeshFormat");

        out.line("$PhysicalNames");
        out.line(std::to_string(names.size()));
        for (const auto& [label, name] : names) out.line("3 " + std::to_string(label) + " \"" + name + "\"");
        out.line("$EndPhysicalNames");

        out.line("$Entities");
        out.size(0), out.size(0), out.size(0), out.size(names.size()), out.endRecord();
        for (const auto& [label, name] : names) {
            const BBox& b = boxes[label];
            out.integer(label);
            for (int k = 0; k < 3; ++k) out.real(b.min[k]);
            for (int k = 0; k < 3; ++k) out.real(b.max[k]);
            out.size(1), out.integer(label), out.size(0), out.endRecord();
        }
        out.endBinaryBlock();
        out.line("$EndEntities");

        out.line("$Nodes");
        out.size(nodesOf.size()), out.size(usedNodes), out.size(minTag), out.size(maxTag), out.endRecord();
        for (const auto& [label, list] : nodesOf) {
            out.integer(3), out.integer(label), out.integer(0), out.size(list.size()), out.endRecord();
            for (std::size_t i : list) out.size(i + 1), out.endRecord();
            for (std::size_t i : list) out.real(nodes[i].x()), out.real(nodes[i].y()), out.real(nodes[i].z()), out.endRecord();
        }
        out.endBinaryBlock();
        out.line("$EndNodes");

        out.line("$Elements");
        out.size(blocks.size()), out.size(tetCount), out.size(tetCount ? 1 : 0), out.size(tetCount), out.endRecord();
        for (const auto& [key, b] : blocks) {
            out.integer(3), out.integer(b.label), out.integer(b.type), out.size(b.tets.size()), out.endRecord();
            const int nn = b.type == 11 ? 10 : 4;
            for (std::size_t t : b.tets) {
                out.size(t + 1);
                for (int k = 0; k < nn; ++k) out.size(static_cast<std::uint64_t>(node(t, k)) + 1);
                out.endRecord();
            }
        }
        out.endBinaryBlock();
        out.line("$EndElements");
    });
}

}  // namespace

void writeGmsh(const TetMesh& mesh, const std::string& path, const GmshWriteOptions& options) {
    writeMsh(mesh.nodes, mesh.tets.size(), mesh.labels, [](std::size_t) { return 4; },
             [&](std::size_t t, int k) { return mesh.tets[t][static_cast<std::size_t>(k)]; }, path, options);
}

void writeGmsh(const MixedTetMesh& mesh, const std::string& path, const GmshWriteOptions& options) {
    if (!mesh.quadratic.empty() && mesh.quadratic.size() != mesh.tets.size())
        throw Error(path, "quadratic flags for " + std::to_string(mesh.quadratic.size()) + " of " +
                              std::to_string(mesh.tets.size()) + " tets");
    writeMsh(
        mesh.nodes, mesh.tets.size(), mesh.labels,
        [&](std::size_t t) { return mesh.quadratic.empty() || mesh.quadratic[t] ? 10 : 4; },
        [&](std::size_t t, int k) { return mesh.tets[t][static_cast<std::size_t>(k)]; }, path, options);
}

}  // namespace jawmesh
