// The tet-mesh editor of tet/TetMeshEditor.h: stars, alive flags, edits and their undo journal.
#include "tet/TetMeshEditor.h"

#include "tet/ElementQuality.h"
#include "tet/SliverScore.h"
#include "tet/TetFaceAdjacency.h"
#include "tet/UnusedNodes.h"

#include <algorithm>
#include <cmath>

namespace jawmesh {

TetMeshEditor::TetMeshEditor(TetMesh& mesh) : mesh_(mesh) {
    alive_.assign(mesh.tets.size(), 1);
    star_.resize(mesh.nodes.size());
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        for (auto v : mesh.tets[t]) star_[std::size_t(v)].push_back(std::int32_t(t));
    fixed_.assign(mesh.nodes.size(), 0);
    const TetFaceAdjacency adj = tetFaceAdjacency(mesh);
    for (std::size_t g = 0; g < adj.groupCount(); ++g) {
        const auto& f0 = adj.faces[std::size_t(adj.groupStart[g])];
        if (!insideOneRegion(adj, mesh, g))
            for (auto v : f0.key) fixed_[std::size_t(v)] = 1;
    }
}

double TetMeshEditor::score(std::int32_t t) const {
    const Tet& e = tet(t);
    return sliverScore(node(e[0]), node(e[1]), node(e[2]), node(e[3]));
}

double TetMeshEditor::volume(std::int32_t t) const {
    const Tet& e = tet(t);
    return signedTetVolume(node(e[0]), node(e[1]), node(e[2]), node(e[3]));
}

bool TetMeshEditor::fillsSameVolume(const std::vector<std::int32_t>& old, const std::vector<Tet>& fresh) const {
    double volOld = 0, volNew = 0;
    for (auto t : old) {
        const Tet& e = tet(t);
        volOld += signedVolume6(node(e[0]), node(e[1]), node(e[2]), node(e[3]));
    }
    for (const Tet& e : fresh) volNew += signedVolume6(node(e[0]), node(e[1]), node(e[2]), node(e[3]));
    return std::abs(volNew - volOld) <= 1e-9 * volOld;
}

std::int32_t TetMeshEditor::acrossFace(std::int32_t t, int k, std::int32_t f[3]) const {
    const Tet& e = tet(t);
    int n = 0;
    for (int j = 0; j < 4; ++j)
        if (j != k) f[n++] = e[std::size_t(j)];
    for (auto s : star(f[0])) {
        if (s == t) continue;
        const Tet& g = tet(s);
        if (std::find(g.begin(), g.end(), f[1]) != g.end() && std::find(g.begin(), g.end(), f[2]) != g.end()) return s;
    }
    return -1;
}

std::int32_t TetMeshEditor::sameRegionNeighbour(std::int32_t t, int k, std::int32_t f[3]) const {
    const std::int32_t s = acrossFace(t, k, f);
    return s >= 0 && label(s) == label(t) ? s : -1;
}

std::vector<std::int32_t> TetMeshEditor::tetsWith(std::int32_t a, std::int32_t b) const {
    std::vector<std::int32_t> out;
    for (auto t : star(a)) {
        const Tet& e = tet(t);
        if (std::find(e.begin(), e.end(), b) != e.end()) out.push_back(t);
    }
    return out;
}

std::vector<std::int32_t> TetMeshEditor::interiorRing(std::int32_t a, std::int32_t b, Label label) const {
    std::vector<std::int32_t> ring = tetsWith(a, b);
    std::vector<std::int32_t> apexCount;  // each ring vertex must appear in exactly two ring tets
    for (auto t : ring) {
        if (this->label(t) != label) return {};
        for (auto v : tet(t))
            if (v != a && v != b) apexCount.push_back(v);
    }
    std::sort(apexCount.begin(), apexCount.end());
    for (std::size_t i = 0; i < apexCount.size();) {
        std::size_t j = i;
        while (j < apexCount.size() && apexCount[j] == apexCount[i]) ++j;
        if (j - i != 2) return {};
        i = j;
    }
    return ring;
}

bool TetMeshEditor::onMeshBoundary(std::int32_t v) const {
    for (auto t : star(v)) {
        const Tet& e = tet(t);
        for (int k = 0; k < 4; ++k) {
            if (e[std::size_t(k)] == v) continue;
            std::int32_t f[3];
            if (acrossFace(t, k, f) < 0) return true;
        }
    }
    return false;
}

void TetMeshEditor::add(const Tet& e, Label label) {
    const auto t = std::int32_t(mesh_.tets.size());
    mesh_.tets.push_back(e);
    mesh_.labels.push_back(label);
    alive_.push_back(1);
    for (auto v : e) star_[std::size_t(v)].push_back(t);
    touched_.push_back(t);
}

void TetMeshEditor::kill(std::int32_t t) {
    recordChange(t);
    alive_[std::size_t(t)] = 0;
    for (auto v : tet(t)) {
        auto& s = star_[std::size_t(v)];
        s.erase(std::find(s.begin(), s.end(), t));
    }
}

void TetMeshEditor::replace(const std::vector<std::int32_t>& old, const std::vector<Tet>& fresh, Label label) {
    for (auto t : old) kill(t);
    for (const Tet& e : fresh) add(e, label);
}

void TetMeshEditor::move(std::int32_t v, const Vec3& p) {
    for (auto t : star(v)) recordChange(t);
    touched_.insert(touched_.end(), star(v).begin(), star(v).end());
    for (Checkpoint& c : checkpoints_) c.movedNodes.emplace_back(v, node(v));
    mesh_.nodes[std::size_t(v)] = p;
}

std::int32_t TetMeshEditor::addNode(const Vec3& p, bool fixed) {
    const auto v = std::int32_t(mesh_.nodes.size());
    mesh_.nodes.push_back(p);
    star_.emplace_back();
    fixed_.push_back(fixed ? 1 : 0);
    return v;
}

void TetMeshEditor::dropNewNode() {
    mesh_.nodes.pop_back();
    star_.pop_back();
    fixed_.pop_back();
}

void TetMeshEditor::recordChange(std::int32_t t) {
    for (Checkpoint& c : checkpoints_) {
        if (std::size_t(t) >= c.firstNewTet) continue;
        bool seen = false;
        for (const auto& o : c.changedTets) seen = seen || o.first == t;
        if (!seen) c.changedTets.emplace_back(t, score(t));
    }
}

void TetMeshEditor::checkpoint() { checkpoints_.push_back({mesh_.tets.size(), mesh_.nodes.size(), {}, {}}); }

void TetMeshEditor::keep() { checkpoints_.pop_back(); }

void TetMeshEditor::rollback() {
    const Checkpoint& c = checkpoints_.back();
    for (std::size_t t = c.firstNewTet; t < mesh_.tets.size(); ++t)
        if (alive_[t])
            for (auto v : mesh_.tets[t]) {
                auto& s = star_[std::size_t(v)];
                s.erase(std::find(s.begin(), s.end(), std::int32_t(t)));
            }
    mesh_.tets.resize(c.firstNewTet);
    mesh_.labels.resize(c.firstNewTet);
    alive_.resize(c.firstNewTet);
    for (auto it = c.changedTets.rbegin(); it != c.changedTets.rend(); ++it)
        if (!alive_[std::size_t(it->first)]) {
            alive_[std::size_t(it->first)] = 1;
            for (auto v : mesh_.tets[std::size_t(it->first)]) star_[std::size_t(v)].push_back(it->first);
        }
    for (auto it = c.movedNodes.rbegin(); it != c.movedNodes.rend(); ++it) {
        mesh_.nodes[std::size_t(it->first)] = it->second;
        if (std::size_t(it->first) < c.firstNewNode)
            touched_.insert(touched_.end(), star_[std::size_t(it->first)].begin(), star_[std::size_t(it->first)].end());
    }
    mesh_.nodes.resize(c.firstNewNode);
    star_.resize(c.firstNewNode);
    fixed_.resize(c.firstNewNode);
    checkpoints_.pop_back();
}

void TetMeshEditor::finish() {
    TetMesh out;
    out.nodes = std::move(mesh_.nodes);
    for (std::size_t t = 0; t < mesh_.tets.size(); ++t)
        if (alive_[t]) {
            out.tets.push_back(mesh_.tets[t]);
            out.labels.push_back(mesh_.labels[t]);
        }
    mesh_ = std::move(out);
    dropUnusedNodes(mesh_);
}

}  // namespace jawmesh
