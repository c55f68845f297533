// Implements tet/ValidateTetMesh.h; what it computes, its rules and its contract are documented there.
#include "tet/ValidateTetMesh.h"

#include "io/Error.h"
#include "tet/TetFaceAdjacency.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <numeric>
#include <cmath>
#include <limits>

namespace jawmesh {
namespace {

std::string at(const Vec3& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
    return buf;
}

bool isJawLabel(Label l) {
    try {
        return labelKind(l) != LabelKind::Outside;
    } catch (const Error&) {
        return false;
    }
}

std::string unnList(const std::vector<int>& v) {
    std::string s;
    for (int u : v) s += (s.empty() ? "" : ", ") + std::to_string(u);
    return s;
}

void checkIndicesAndLabels(const TetMesh& m, ValidationReport& r) {
    if (m.labels.size() != m.tets.size()) {
        r.sizeMismatch = 1;
        r.messages.push_back(std::to_string(m.labels.size()) + " labels for " + std::to_string(m.tets.size()) + " tets");
    }
    const auto nn = static_cast<std::int64_t>(m.nodes.size());
    std::int64_t firstBad = -1;
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        const Tet& e = m.tets[t];
        bool bad = false;
        for (int i = 0; i < 4; ++i) {
            if (e[static_cast<std::size_t>(i)] < 0 || e[static_cast<std::size_t>(i)] >= nn) bad = true;
            for (int j = i + 1; j < 4; ++j)
                if (e[static_cast<std::size_t>(i)] == e[static_cast<std::size_t>(j)]) bad = true;
        }
        if (bad) {
            ++r.badIndices;
            if (firstBad < 0) firstBad = static_cast<std::int64_t>(t);
        }
    }
    if (r.badIndices)
        r.messages.push_back(std::to_string(r.badIndices) + " tets with node indices out of range or repeated (first: tet " +
                             std::to_string(firstBad) + ")");
    const std::size_t nl = std::min(m.labels.size(), m.tets.size());
    for (std::size_t t = 0; t < nl; ++t) ++r.tetsPerLabel[m.labels[t]];
    std::string unknown;
    for (const auto& [label, count] : r.tetsPerLabel) {
        if (isJawLabel(label)) continue;
        r.unknownLabels += count;
        unknown += (unknown.empty() ? "" : ", ") + std::to_string(label);
    }
    if (r.unknownLabels) r.messages.push_back(std::to_string(r.unknownLabels) + " tets with labels that are not jaw regions: " + unknown);
}

void checkOrientation(const TetMesh& m, ValidationReport& r) {
    std::atomic<std::size_t> inverted{0}, degenerate{0};
    std::atomic<std::int64_t> firstInverted{std::numeric_limits<std::int64_t>::max()}, firstDegenerate{std::numeric_limits<std::int64_t>::max()};
    auto lowerTo = [](std::atomic<std::int64_t>& a, std::int64_t v) {
        std::int64_t cur = a.load();
        while (v < cur && !a.compare_exchange_weak(cur, v)) {}
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.tets.size()), [&](const tbb::blocked_range<std::size_t>& range) {
        std::size_t inv = 0, deg = 0;
        for (std::size_t t = range.begin(); t != range.end(); ++t) {
            const Tet& e = m.tets[t];
            const Vec3& a = m.nodes[static_cast<std::size_t>(e[0])];
            const Vec3 u = m.nodes[static_cast<std::size_t>(e[1])] - a, v = m.nodes[static_cast<std::size_t>(e[2])] - a,
                       w = m.nodes[static_cast<std::size_t>(e[3])] - a;
            const double det = u.dot(v.cross(w));
            const double longest2 = std::max({u.squaredNorm(), v.squaredNorm(), w.squaredNorm(), (v - u).squaredNorm(),
                                              (w - u).squaredNorm(), (w - v).squaredNorm()});
            // A 10-degree sliver has |6V| / L^3 around 1e-2; 1e-9 only catches flat elements.
            const double tol = 1e-9 * longest2 * std::sqrt(longest2);
            if (std::abs(det) <= tol) {
                ++deg;
                lowerTo(firstDegenerate, static_cast<std::int64_t>(t));
            } else if (det < 0) {
                ++inv;
                lowerTo(firstInverted, static_cast<std::int64_t>(t));
            }
        }
        inverted += inv;
        degenerate += deg;
    });
    r.invertedTets = inverted;
    r.degenerateTets = degenerate;
    if (r.invertedTets)
        r.messages.push_back(std::to_string(r.invertedTets) + " inverted tets (first: tet " + std::to_string(firstInverted.load()) +
                             " at " + at(m.nodes[static_cast<std::size_t>(m.tets[static_cast<std::size_t>(firstInverted.load())][0])]) + ")");
    if (r.degenerateTets)
        r.messages.push_back(std::to_string(r.degenerateTets) + " zero-volume tets (first: tet " + std::to_string(firstDegenerate.load()) +
                             " at " + at(m.nodes[static_cast<std::size_t>(m.tets[static_cast<std::size_t>(firstDegenerate.load())][0])]) + ")");
}

/// Returns, per node, the lowest index of a used node at exactly the same position (itself when
/// unique); counts unused nodes and duplicates.
std::vector<std::int32_t> canonicalNodes(const TetMesh& m, ValidationReport& r) {
    std::vector<char> used(m.nodes.size(), 0);
    for (const Tet& e : m.tets)
        for (auto v : e) used[static_cast<std::size_t>(v)] = 1;
    std::vector<std::int32_t> order;
    order.reserve(m.nodes.size());
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
        if (used[i]) order.push_back(static_cast<std::int32_t>(i));
        else ++r.unusedNodes;
    }
    tbb::parallel_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
        const Vec3& p = m.nodes[static_cast<std::size_t>(a)];
        const Vec3& q = m.nodes[static_cast<std::size_t>(b)];
        if (p.x() != q.x()) return p.x() < q.x();
        if (p.y() != q.y()) return p.y() < q.y();
        if (p.z() != q.z()) return p.z() < q.z();
        return a < b;
    });
    std::vector<std::int32_t> canon(m.nodes.size());
    std::iota(canon.begin(), canon.end(), 0);
    std::int64_t example = -1;
    for (std::size_t k = 1; k < order.size(); ++k) {
        const auto prev = static_cast<std::size_t>(order[k - 1]), cur = static_cast<std::size_t>(order[k]);
        if (m.nodes[prev] == m.nodes[cur]) {
            canon[cur] = canon[prev];
            ++r.duplicateNodes;
            if (example < 0) example = static_cast<std::int64_t>(cur);
        }
    }
    if (r.duplicateNodes)
        r.messages.push_back(std::to_string(r.duplicateNodes) + " duplicate nodes (first: node " + std::to_string(example) + " at " +
                             at(m.nodes[static_cast<std::size_t>(example)]) + ")");
    return canon;
}

void checkFaces(const TetMesh& m, const std::vector<std::int32_t>& canon, ValidationReport& r) {
    const TetFaceAdjacency adj = tetFaceAdjacency(m);
    std::int64_t exampleNonManifold = -1;
    const std::size_t ng = adj.groupCount();
    std::int64_t examplePdl = -1;
    for (std::size_t g = 0; g < ng; ++g) {
        const std::size_t begin = static_cast<std::size_t>(adj.groupStart[g]);
        const std::size_t size = adj.groupSize(g);
        const TetFaceRef& f0 = adj.faces[begin];
        if (size > 2) {
            ++r.nonManifoldFaces;
            if (exampleNonManifold < 0) exampleNonManifold = static_cast<std::int64_t>(g);
            continue;
        }
        const Label a = m.labels[static_cast<std::size_t>(f0.tet)];
        const Label b = size == 2 ? m.labels[static_cast<std::size_t>(adj.faces[begin + 1].tet)] : kOutsideLabel;
        if (size == 1) ++r.boundaryFaces;
        else if (a == b) ++r.interiorFaces;
        else ++r.interfaceFaces;
        if (a == b) continue;
        const Label lo = std::min(a, b), hi = std::max(a, b);
        ++r.interfaceFacesPerPair[{lo, hi}];
        // A PDL may touch its own tooth, bone and the outside only.
        bool foreign = false;
        for (const auto& [p, other] : {std::pair<Label, Label>{a, b}, std::pair<Label, Label>{b, a}}) {
            if (!isJawLabel(p) || labelKind(p) != LabelKind::Pdl) continue;
            const bool ok = other == kOutsideLabel || (isJawLabel(other) && labelKind(other) == LabelKind::Bone) ||
                            (isJawLabel(other) && labelKind(other) == LabelKind::Tooth && labelUnn(other) == labelUnn(p));
            foreign = foreign || !ok;
        }
        if (foreign) {
            ++r.pdlForeignContacts;
            if (examplePdl < 0) examplePdl = static_cast<std::int64_t>(g);
        }
    }
    auto faceAt = [&](std::int64_t g) {
        const auto& key = adj.faces[static_cast<std::size_t>(adj.groupStart[static_cast<std::size_t>(g)])].key;
        return at((m.nodes[static_cast<std::size_t>(key[0])] + m.nodes[static_cast<std::size_t>(key[1])] +
                   m.nodes[static_cast<std::size_t>(key[2])]) / 3.0);
    };
    if (r.nonManifoldFaces)
        r.messages.push_back(std::to_string(r.nonManifoldFaces) + " faces shared by more than two tets (first at " +
                             faceAt(exampleNonManifold) + ")");
    if (r.pdlForeignContacts) {
        const auto& f = adj.faces[static_cast<std::size_t>(adj.groupStart[static_cast<std::size_t>(examplePdl)])];
        const std::size_t begin = static_cast<std::size_t>(adj.groupStart[static_cast<std::size_t>(examplePdl)]);
        const Label a = m.labels[static_cast<std::size_t>(f.tet)];
        const Label b = adj.groupSize(static_cast<std::size_t>(examplePdl)) == 2 ? m.labels[static_cast<std::size_t>(adj.faces[begin + 1].tet)] : 0;
        auto name = [](Label l) { return isJawLabel(l) ? labelName(l) : std::to_string(l); };
        r.messages.push_back(std::to_string(r.pdlForeignContacts) + " faces where a PDL touches a region other than its tooth, bone or outside (first: " +
                             name(a) + " / " + name(b) + " at " + faceAt(examplePdl) + ")");
    }

    // Coincident faces: only faces touching a duplicated node can coincide with another face.
    if (r.duplicateNodes == 0) return;
    std::vector<char> inDupGroup(m.nodes.size(), 0);
    for (std::size_t i = 0; i < canon.size(); ++i)
        if (canon[i] != static_cast<std::int32_t>(i)) inDupGroup[i] = inDupGroup[static_cast<std::size_t>(canon[i])] = 1;
    std::vector<std::pair<std::array<std::int32_t, 3>, std::size_t>> keyed;  // canonical key, group
    for (std::size_t g = 0; g < ng; ++g) {
        const auto& key = adj.faces[static_cast<std::size_t>(adj.groupStart[g])].key;
        if (!inDupGroup[static_cast<std::size_t>(key[0])] && !inDupGroup[static_cast<std::size_t>(key[1])] &&
            !inDupGroup[static_cast<std::size_t>(key[2])])
            continue;
        std::array<std::int32_t, 3> c = {canon[static_cast<std::size_t>(key[0])], canon[static_cast<std::size_t>(key[1])],
                                         canon[static_cast<std::size_t>(key[2])]};
        std::sort(c.begin(), c.end());
        keyed.emplace_back(c, g);
    }
    std::sort(keyed.begin(), keyed.end());
    std::int64_t example = -1;
    for (std::size_t i = 0; i < keyed.size();) {
        std::size_t j = i + 1;
        while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
        if (j - i > 1) {
            r.coincidentFaces += j - i;
            if (example < 0) example = static_cast<std::int64_t>(keyed[i].second);
        }
        i = j;
    }
    if (r.coincidentFaces)
        r.messages.push_back(std::to_string(r.coincidentFaces) + " faces coincide with another face without sharing its nodes (first at " +
                             faceAt(example) + "): the regions are not conformal there");
}

void checkTeeth(const TetMesh& m, const std::vector<int>& expected, ValidationReport& r) {
    for (int unn : expected) {
        if (!isValidUnn(unn)) {
            r.missingTeeth.push_back(unn);
            continue;
        }
        if (r.tetsPerLabel.count(implantLabel(unn))) {  // an implant in its place: fused, no PDL
            const Label implant = implantLabel(unn);
            if (!r.interfaceFacesPerPair.count({kMandibleBoneLabel, implant}) &&
                !r.interfaceFacesPerPair.count({kMaxillaBoneLabel, implant}))
                r.unfusedImplants.push_back(unn);
            continue;
        }
        if (!r.tetsPerLabel.count(toothLabel(unn))) r.missingTeeth.push_back(unn);
        if (!r.tetsPerLabel.count(pdlLabel(unn))) r.missingPdls.push_back(unn);
    }
    if (!r.unfusedImplants.empty()) r.messages.push_back("implants sharing no face with the bone: " + unnList(r.unfusedImplants));
    if (!r.missingTeeth.empty()) r.messages.push_back("expected teeth missing: " + unnList(r.missingTeeth));
    if (!r.missingPdls.empty()) r.messages.push_back("PDL missing for teeth: " + unnList(r.missingPdls));

    // Distinct teeth (tooth or PDL of different UNN) never share a node.
    std::map<Label, int> unnOf;
    for (const auto& [label, count] : r.tetsPerLabel) {
        if (!isJawLabel(label)) continue;
        const LabelKind k = labelKind(label);
        unnOf[label] = (isToothLike(k) || k == LabelKind::Pdl) ? labelUnn(label) : 0;
    }
    std::vector<std::int8_t> owner(m.nodes.size(), 0);
    std::vector<char> conflict(m.nodes.size(), 0);
    for (std::size_t t = 0; t < m.tets.size(); ++t) {
        const auto it = unnOf.find(m.labels[t]);
        if (it == unnOf.end() || it->second == 0) continue;
        const auto u = static_cast<std::int8_t>(it->second);
        for (auto v : m.tets[t]) {
            auto& o = owner[static_cast<std::size_t>(v)];
            if (o == 0) o = u;
            else if (o != u) conflict[static_cast<std::size_t>(v)] = 1;
        }
    }
    std::int64_t example = -1;
    for (std::size_t i = 0; i < conflict.size(); ++i) {
        if (!conflict[i]) continue;
        ++r.teethSharingNodes;
        if (example < 0) example = static_cast<std::int64_t>(i);
    }
    if (r.teethSharingNodes)
        r.messages.push_back(std::to_string(r.teethSharingNodes) + " nodes shared by two different teeth (first: node " +
                             std::to_string(example) + " at " + at(m.nodes[static_cast<std::size_t>(example)]) + ")");
}

}  // namespace

std::size_t ValidationReport::violationCount() const {
    return badIndices + unknownLabels + sizeMismatch + nonManifoldFaces + duplicateNodes + coincidentFaces + invertedTets +
           degenerateTets + missingTeeth.size() + missingPdls.size() + unfusedImplants.size() + pdlForeignContacts + teethSharingNodes;
}

ValidationReport validateTetMesh(const TetMesh& mesh, const std::vector<int>& expectedTeethUnn) {
    ValidationReport r;
    r.nodes = mesh.nodes.size();
    r.tets = mesh.tets.size();
    checkIndicesAndLabels(mesh, r);
    if (r.badIndices || r.sizeMismatch) return r;  // the other checks would index out of range
    checkOrientation(mesh, r);
    const std::vector<std::int32_t> canon = canonicalNodes(mesh, r);
    checkFaces(mesh, canon, r);
    checkTeeth(mesh, expectedTeethUnn, r);
    return r;
}

ValidationReport requireValid(const TetMesh& mesh, const std::vector<int>& expectedTeethUnn) {
    ValidationReport r = validateTetMesh(mesh, expectedTeethUnn);
    if (!r.valid()) {
        std::string reason = "invalid tet mesh (" + std::to_string(r.violationCount()) + " violations)";
        for (const auto& msg : r.messages) reason += "; " + msg;
        throw Error("tet mesh", reason);
    }
    return r;
}

nlohmann::json toJson(const ValidationReport& r) {
    nlohmann::json j;
    j["valid"] = r.valid();
    j["nodes"] = r.nodes;
    j["tets"] = r.tets;
    j["unused_nodes"] = r.unusedNodes;
    j["boundary_faces"] = r.boundaryFaces;
    j["interface_faces"] = r.interfaceFaces;
    j["interior_faces"] = r.interiorFaces;
    nlohmann::json perLabel = nlohmann::json::object();
    for (const auto& [label, count] : r.tetsPerLabel) perLabel[std::to_string(label)] = count;
    j["tets_per_label"] = perLabel;
    nlohmann::json pairs = nlohmann::json::object();
    for (const auto& [pair, count] : r.interfaceFacesPerPair)
        pairs[std::to_string(pair.first) + "-" + std::to_string(pair.second)] = count;
    j["interface_faces_per_pair"] = pairs;
    j["violations"] = {{"bad_indices", r.badIndices},
                       {"unknown_labels", r.unknownLabels},
                       {"size_mismatch", r.sizeMismatch},
                       {"non_manifold_faces", r.nonManifoldFaces},
                       {"duplicate_nodes", r.duplicateNodes},
                       {"coincident_faces", r.coincidentFaces},
                       {"inverted_tets", r.invertedTets},
                       {"degenerate_tets", r.degenerateTets},
                       {"missing_teeth", r.missingTeeth},
                       {"missing_pdls", r.missingPdls},
                       {"unfused_implants", r.unfusedImplants},
                       {"pdl_foreign_contacts", r.pdlForeignContacts},
                       {"teeth_sharing_nodes", r.teethSharingNodes}};
    j["violation_count"] = r.violationCount();
    j["messages"] = r.messages;
    return j;
}

}  // namespace jawmesh
