// Implements tet/TetgenGroups.h; what it computes, its rules and its contract are documented there.
#include "tet/TetgenGroups.h"

#include "io/Error.h"
#include "io/ParallelInOrder.h"
#include "tet/LabelFromSides.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <map>
#include <optional>

namespace jawmesh {
namespace {

constexpr int kGroups = 2;

/// Per label, its group (labels missing from the map: outside).
using Groups = std::map<Label, int>;

bool inGroup(const Groups& groups, Label label, int group) {
    const auto it = groups.find(label);
    return it != groups.end() && it->second == group;
}

/// The part of a complex one group's run is given: the triangles with a side in the group, the
/// points they use (in plc's order) and the group's seeds with their volume bounds.
struct GroupRun {
    InterfaceComplex complex;
    std::vector<std::int32_t> plcPoint;  ///< per point of `complex`, its index in plc
    TetgenRun run;
};

GroupRun groupRun(const InterfaceComplex& plc, const TetgenRun& run, const Groups& groups, int group) {
    GroupRun g;
    g.run.switches = run.switches;
    g.run.optMaxDihedralDeg = run.optMaxDihedralDeg;
    const auto& S = plc.surface;
    std::vector<std::int32_t> local(S.vertices.size(), -1);
    for (std::size_t t = 0; t < S.triangles.size(); ++t)
        if (inGroup(groups, plc.sides[t][0], group) || inGroup(groups, plc.sides[t][1], group))
            for (std::int32_t v : S.triangles[t]) local[std::size_t(v)] = 0;
    for (std::size_t v = 0; v < local.size(); ++v)
        if (local[v] >= 0) {
            local[v] = std::int32_t(g.plcPoint.size());
            g.plcPoint.push_back(std::int32_t(v));
            g.complex.surface.vertices.push_back(S.vertices[v]);
        }
    for (std::size_t t = 0; t < S.triangles.size(); ++t) {
        if (!inGroup(groups, plc.sides[t][0], group) && !inGroup(groups, plc.sides[t][1], group)) continue;
        Tri f = S.triangles[t];
        for (auto& v : f) v = local[std::size_t(v)];
        g.complex.surface.triangles.push_back(f);
        g.complex.sides.push_back(plc.sides[t]);
    }
    for (std::size_t r = 0; r < plc.seeds.size(); ++r)
        if (inGroup(groups, plc.seeds[r].label, group)) {
            g.complex.seeds.push_back(plc.seeds[r]);
            g.run.seedVolumeBoundsMm3.push_back(run.seedVolumeBoundsMm3.at(r));
        }
    return g;
}

/// Appends the group's tets (`raw` labeled from the group's sides; those of its own regions only),
/// its Steiner points and its facets to `merged`, in plc's numbering.
void appendGroup(const GroupRun& g, const TetgenMesh& raw, const Groups& groups, int group, TetgenMesh& merged) {
    const std::size_t points = g.plcPoint.size();
    const std::size_t base = merged.mesh.nodes.size();
    const auto plcIndex = [&](std::int32_t id) {
        return std::size_t(id) < points ? g.plcPoint[std::size_t(id)] : std::int32_t(base + std::size_t(id) - points);
    };
    merged.mesh.nodes.insert(merged.mesh.nodes.end(), raw.mesh.nodes.begin() + std::ptrdiff_t(points), raw.mesh.nodes.end());
    for (std::size_t t = 0; t < raw.mesh.tets.size(); ++t) {
        if (!inGroup(groups, raw.mesh.labels[t], group)) continue;
        Tet e = raw.mesh.tets[t];
        for (auto& v : e) v = plcIndex(v);
        merged.mesh.tets.push_back(e);
        merged.mesh.labels.push_back(raw.mesh.labels[t]);
    }
    for (auto f : raw.facets) {
        for (auto& v : f) v = plcIndex(v);
        std::sort(f.begin(), f.end());
        merged.facets.push_back(f);
    }
}

/// Both groups' runs: at once when the task arena has more than one thread, group 1 in a child
/// (file comment) while group 0 runs here, else in turn here; both in children when isolated.
/// Every child is forked before TetGen runs here, from this thread alone (ForkedChild: a fork
/// beside a thread inside malloc hangs under the sanitizers). A child that cannot be started (no
/// fork: out of processes or memory) costs only the parallelism.
std::vector<TetgenMesh> runGroups(const std::vector<GroupRun>& groups, bool isolated, std::uint64_t& childPeakBytes) {
    std::vector<TetgenMesh> raw(kGroups);
    if (tbb::this_task_arena::max_concurrency() <= 1) {
        for (int g = 0; g < kGroups; ++g) {
            const GroupRun& G = groups[std::size_t(g)];
            raw[std::size_t(g)] = isolated ? runTetgenInChild(G.complex, G.run, childPeakBytes) : runTetgen(G.complex, G.run);
        }
        return raw;
    }
    std::vector<std::optional<ForkedChild>> children(kGroups);
    for (int g = isolated ? 0 : 1; g < kGroups; ++g) {
        const GroupRun& G = groups[std::size_t(g)];
        try {
            children[std::size_t(g)].emplace(startTetgenInChild(G.complex, G.run));
        } catch (const Error&) {
            if (isolated) throw;  // else group g runs here after group 0
        }
    }
    for (int g = 0; g < kGroups; ++g) {
        const GroupRun& G = groups[std::size_t(g)];
        auto& child = children[std::size_t(g)];
        raw[std::size_t(g)] = child ? finishTetgenInChild(*child, G.run, childPeakBytes) : runTetgen(G.complex, G.run);
    }
    return raw;
}

}  // namespace

std::map<Label, int> tetgenGroups(const InterfaceComplex& plc) {
    std::map<Label, std::size_t> triangles;
    for (const auto& sides : plc.sides)
        for (Label l : sides)
            if (l != kOutsideLabel) ++triangles[l];
    std::vector<std::pair<std::size_t, Label>> byCost;
    for (const auto& [label, n] : triangles) byCost.emplace_back(n, label);
    // largest first, ties by label: the same groups whatever the order of the complex
    std::sort(byCost.begin(), byCost.end(),
              [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
    std::map<Label, int> groups;
    std::size_t load[kGroups] = {};
    for (const auto& [n, label] : byCost) {
        const int g = load[1] < load[0] ? 1 : 0;
        groups[label] = g;
        load[g] += n;
    }
    return groups;
}

TetgenMesh runTetgenInGroups(const InterfaceComplex& plc, const TetgenRun& run, bool preserveBoundary, bool isolated,
                             std::uint64_t& childPeakBytes) {
    const auto single = [&] {
        TetgenMesh raw = isolated ? runTetgenInChild(plc, run, childPeakBytes) : runTetgen(plc, run);
        if (preserveBoundary) labelFromSides(plc, raw);
        return raw;
    };
    if (!preserveBoundary) return single();
    const Groups labelGroups = tetgenGroups(plc);
    std::vector<GroupRun> groups;
    for (int g = 0; g < kGroups; ++g) groups.push_back(groupRun(plc, run, labelGroups, g));
    for (const GroupRun& g : groups)
        if (g.complex.seeds.empty()) return single();

    std::vector<TetgenMesh> raw = runGroups(groups, isolated, childPeakBytes);
    // Each group labeled from its own sides, both at once. The union needs no labelling of its
    // own: a region's tets are all in its group, bounded by triangles all in that group's complex.
    parallelForFirstErrorInOrder(std::size_t(kGroups), [&](std::size_t g) { labelFromSides(groups[g].complex, raw[g]); });
    TetgenMesh merged;
    merged.mesh.nodes = plc.surface.vertices;
    for (int g = 0; g < kGroups; ++g) appendGroup(groups[std::size_t(g)], raw[std::size_t(g)], labelGroups, g, merged);
    std::sort(merged.facets.begin(), merged.facets.end());
    merged.facets.erase(std::unique(merged.facets.begin(), merged.facets.end()), merged.facets.end());
    return merged;
}

}  // namespace jawmesh
