// Implements filters/WellComposedLabels.h; what it computes, its rules and its contract are documented there.
#include "filters/WellComposedLabels.h"

#include "filters/LabelEdges.h"
#include "io/Error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <limits>
#include <tuple>

namespace jawmesh {
namespace {

// The six faces of a dual cell as corner indices in cyclic order.
constexpr int kFaces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                              {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};

struct Fix {
    openvdb::Coord voxel;
    Label to;
};

class DistanceLookup {
public:
    explicit DistanceLookup(const std::map<Label, openvdb::FloatGrid::Ptr>& d) : d_(d) {}
    double operator()(Label label, const openvdb::Coord& v) const {
        const auto it = d_.find(label);
        if (it == d_.end() || !it->second) return 0.0;
        return it->second->tree().getValue(v);
    }

private:
    const std::map<Label, openvdb::FloatGrid::Ptr>& d_;
};

bool higher(Label a, Label b) {  // a connects before b
    const int pa = labelConnectPriority(a), pb = labelConnectPriority(b);
    return pa != pb ? pa > pb : a < b;
}

// Among corners `cand` of the cell, the voxel to give away: lowest priority, shallowest, lowest.
int pickVictim(const std::vector<int>& cand, const std::array<Label, 8>& lab,
               const std::array<openvdb::Coord, 8>& xyz, const DistanceLookup& dist) {
    int best = cand[0];
    for (std::size_t i = 1; i < cand.size(); ++i) {
        const int k = cand[i];
        if (lab[k] != lab[best]) {
            if (higher(lab[best], lab[k])) best = k;
            continue;
        }
        const double dk = dist(lab[k], xyz[k]), db = dist(lab[best], xyz[best]);
        if (dk > db || (dk == db && xyz[k] < xyz[best])) best = k;
    }
    return best;
}

// Highest-priority label among corners `cand`.
Label highestOf(const std::vector<int>& cand, const std::array<Label, 8>& lab) {
    Label best = lab[cand[0]];
    for (int k : cand)
        if (higher(lab[k], best)) best = lab[k];
    return best;
}

// One fix for a critical cell, or none. Every fix relabels a voxel to a label of strictly higher
// priority, so the repair terminates. Regions are examined in label order; the first critical one
// decides.
bool fixCell(const std::array<Label, 8>& lab, const std::array<openvdb::Coord, 8>& xyz,
             const DistanceLookup& dist, Fix& fix) {
    std::array<Label, 8> distinct = lab;
    std::sort(distinct.begin(), distinct.end());
    const auto end = std::unique(distinct.begin(), distinct.end());
    if (end - distinct.begin() < 2) return false;
    // L is joined through a separator voxel below it, or else one of its own voxels is cut off
    // (raised to the highest separator label next to it).
    const auto joinOrCut = [&](Label L, const std::vector<int>& own, const std::vector<int>& sep) {
        std::vector<int> below;
        for (int k : sep)
            if (higher(L, lab[k])) below.push_back(k);
        if (!below.empty()) {
            fix = {xyz[pickVictim(below, lab, xyz, dist)], L};
            return;
        }
        const int v = pickVictim(own, lab, xyz, dist);
        std::vector<int> next;
        for (int k : sep)
            if (__builtin_popcount(unsigned(k ^ v)) == 1) next.push_back(k);
        fix = {xyz[v], highestOf(next.empty() ? sep : next, lab)};
    };
    for (auto it = distinct.begin(); it != end; ++it) {
        const Label L = *it;
        // (a) L on one face diagonal, absent from the other
        for (const auto& f : kFaces) {
            for (int s = 0; s < 2; ++s) {
                const int a = f[s], b = f[s + 2], c = f[s + 1], d = f[(s + 3) % 4];
                if (lab[a] != L || lab[b] != L || lab[c] == L || lab[d] == L) continue;
                joinOrCut(L, {a, b}, {c, d});
                return true;
            }
        }
        // (b) L on exactly two opposite corners, or absent from exactly two opposite corners
        int count = 0;
        for (int k = 0; k < 8; ++k) count += lab[k] == L;
        for (int k = 0; k < 4; ++k) {
            const int o = 7 - k;
            if (count == 2 && lab[k] == L && lab[o] == L) {
                std::vector<int> sep;
                for (int m = 0; m < 8; ++m)
                    if (m != k && m != o) sep.push_back(m);
                joinOrCut(L, {k, o}, sep);
                return true;
            }
            if (count == 6 && lab[k] != L && lab[o] != L && lab[k] != lab[o]) {
                // L's complement touches itself at the centre only: fill a corner with L, or, when
                // both corners rank above L, grow the lower-ranked corner's region into L
                std::vector<int> below;
                for (int m : {k, o})
                    if (higher(L, lab[m])) below.push_back(m);
                if (!below.empty()) {
                    fix = {xyz[pickVictim(below, lab, xyz, dist)], L};
                } else {
                    const int c = higher(lab[k], lab[o]) ? o : k;
                    fix = {xyz[pickVictim({c ^ 1, c ^ 2, c ^ 4}, lab, xyz, dist)], lab[c]};
                }
                return true;
            }
        }
    }
    return false;
}

/// The dual cells that have one of `voxels` as a corner, sorted.
std::vector<openvdb::Coord> cellsAround(const std::vector<openvdb::Coord>& voxels) {
    std::vector<openvdb::Coord> cells;
    cells.reserve(8 * voxels.size());
    for (const openvdb::Coord& v : voxels)
        for (int k = 0; k < 8; ++k) cells.push_back(v - openvdb::Coord(k & 1, (k >> 1) & 1, k >> 2));
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    return cells;
}

/// Fixes for the critical cells among `cells`.
std::vector<Fix> proposeFixes(const openvdb::Int32Grid& labels,
                              const std::map<Label, openvdb::FloatGrid::Ptr>& distances,
                              const std::vector<openvdb::Coord>& cells, Progress& progress) {
    std::vector<std::vector<Fix>> chunks((cells.size() + 4095) / 4096);
    tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t chunk) {
        progress.checkCancelled();
        auto acc = labels.getConstAccessor();
        const DistanceLookup dist(distances);
        const std::size_t lo = chunk * 4096, hi = std::min(cells.size(), lo + 4096);
        for (std::size_t i = lo; i < hi; ++i) {
            std::array<Label, 8> lab;
            std::array<openvdb::Coord, 8> xyz;
            for (int k = 0; k < 8; ++k) {
                xyz[k] = dualCellCorner(cells[i], k);
                lab[k] = acc.getValue(xyz[k]);
            }
            Fix fix;
            if (fixCell(lab, xyz, dist, fix)) chunks[chunk].push_back(fix);
        }
    });
    std::vector<Fix> fixes;
    for (const auto& c : chunks) fixes.insert(fixes.end(), c.begin(), c.end());
    // one fix per voxel: the highest-priority target wins
    std::sort(fixes.begin(), fixes.end(), [](const Fix& a, const Fix& b) {
        if (a.voxel != b.voxel) return a.voxel < b.voxel;
        return higher(a.to, b.to);
    });
    fixes.erase(std::unique(fixes.begin(), fixes.end(),
                            [](const Fix& a, const Fix& b) { return a.voxel == b.voxel; }),
                fixes.end());
    return fixes;
}

}  // namespace

int labelConnectPriority(Label label) {
    switch (labelKind(label)) {
        case LabelKind::Pdl: return 3;
        case LabelKind::Tooth:
        case LabelKind::Implant: return 2;
        case LabelKind::Bone: return 1;
        case LabelKind::Outside: return 0;
    }
    return 0;
}

namespace {

/// The repair sweeps, starting from the dual cells `cells`.
std::size_t repairCells(openvdb::Int32Grid& labels, const std::map<Label, openvdb::FloatGrid::Ptr>& distances,
                        std::vector<openvdb::Coord> cells, Progress& progress, std::vector<openvdb::Coord>* out) {
    std::size_t relabelled = 0;
    // After the first sweep only the cells around what it changed are looked at again: a cell
    // none of whose corners changed is as it was, and every critical cell changed a corner.
    std::vector<openvdb::Coord> fixed;
    for (int sweep = 0; sweep < 256; ++sweep) {
        progress.checkCancelled();
        const auto fixes = proposeFixes(labels, distances, cells, progress);
        if (fixes.empty()) return relabelled;
        fixed.clear();
        for (const Fix& f : fixes) fixed.push_back(f.voxel);
        if (out) out->insert(out->end(), fixed.begin(), fixed.end());
        cells = cellsAround(fixed);
        auto acc = labels.getAccessor();
        for (const Fix& f : fixes) acc.setValue(f.voxel, f.to);
        relabelled += fixes.size();
    }
    throw Error("label field: diagonal contacts between regions could not be removed in 256 sweeps");
}

}  // namespace

std::size_t makeLabelsWellComposed(openvdb::Int32Grid& labels,
                                   const std::map<Label, openvdb::FloatGrid::Ptr>& distances,
                                   Progress& progress, const std::vector<openvdb::Coord>* changedVoxels,
                                   std::vector<openvdb::Coord>* relabelled) {
    return repairCells(labels, distances,
                       changedVoxels ? cellsAround(*changedVoxels) : dualCellsOf(findLabelEdges(labels)),
                       progress, relabelled);
}

std::size_t makeLabelsWellComposed(openvdb::Int32Grid& labels,
                                   const std::map<Label, openvdb::FloatGrid::Ptr>& distances,
                                   const std::vector<LabelEdge>& edges, Progress& progress,
                                   std::vector<openvdb::Coord>* relabelled) {
    return repairCells(labels, distances, dualCellsOf(edges), progress, relabelled);
}

std::size_t countCriticalCells(const openvdb::Int32Grid& labels,
                               const std::map<Label, openvdb::FloatGrid::Ptr>& distances) {
    return proposeFixes(labels, distances, dualCellsOf(findLabelEdges(labels)), noProgress()).size();
}

}  // namespace jawmesh
