// Implements filters/SmallComponents.h; what it computes, its rules and its contract are documented there.
#include "filters/SmallComponents.h"

#include "filters/LabelEdges.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <set>
#include <vector>

namespace jawmesh {
namespace {

using openvdb::Coord;

const Coord kFace[6] = {Coord(1, 0, 0), Coord(-1, 0, 0), Coord(0, 1, 0), Coord(0, -1, 0), Coord(0, 0, 1), Coord(0, 0, -1)};

struct SmallComponent {
    Label label;
    Label fill;
    std::vector<Coord> voxels;
};

/// The small components that the starts [begin, end) meet (in the order of their first start in
/// it) and the labels of the large components they meet.
struct ChunkComponents {
    std::vector<SmallComponent> small;
    std::set<Label> hasLarge;
};

/// Flood fills bounded by the limits from every start not yet reached.
ChunkComponents findSmallComponents(const openvdb::Int32Grid& labels, const Coord* begin, const Coord* end,
                                    std::size_t maxOutsideVoxels, std::size_t maxRegionVoxels) {
    // 1 = in a component larger than its limit, 2 = in a small one, 3 = in the current flood.
    openvdb::Int32Grid seen(0);
    auto seenAcc = seen.getAccessor();
    auto acc = labels.getConstAccessor();
    ChunkComponents out;
    std::vector<Coord> component;
    for (const Coord* start = begin; start != end; ++start) {
        if (seenAcc.getValue(*start) != 0) continue;
        const Label L = acc.getValue(*start);
        const std::size_t limit = L == kOutsideLabel ? maxOutsideVoxels : maxRegionVoxels;
        component.assign(1, *start);
        seenAcc.setValue(*start, 3);
        bool large = limit == 0;
        for (std::size_t i = 0; i < component.size() && !large; ++i)
            for (const Coord& d : kFace) {
                const Coord n = component[i] + d;
                if (acc.getValue(n) != L) continue;
                const int s = seenAcc.getValue(n);
                if (s == 1 || (s == 0 && component.size() >= limit)) {
                    large = true;
                    break;
                }
                if (s != 0) continue;
                seenAcc.setValue(n, 3);
                component.push_back(n);
            }
        for (const Coord& c : component) seenAcc.setValue(c, large ? 1 : 2);
        if (large) {
            out.hasLarge.insert(L);
            continue;
        }
        std::map<Label, std::size_t> around;
        for (const Coord& c : component)
            for (const Coord& d : kFace) {
                const Label n = acc.getValue(c + d);
                if (n != L) ++around[n];
            }
        Label fill = L;
        std::size_t most = 0;
        for (const auto& [n, count] : around)  // ascending labels: ties keep the smaller
            if (count > most) {
                most = count;
                fill = n;
            }
        if (fill != L) out.small.push_back({L, fill, component});
    }
    return out;
}

}  // namespace

SmallComponentStats absorbSmallComponents(openvdb::Int32Grid& labels, std::size_t maxOutsideVoxels,
                                          std::size_t maxRegionVoxels, std::vector<Coord>* relabelled,
                                          const std::vector<LabelEdge>* givenEdges) {
    // The lower voxel of every label edge: every small component holds one (its last voxel along
    // x, say). Sorted with the edges, so components are found in the same order whatever the
    // tree's layout. The label edges find them in parallel and skip the inside of leaves that hold
    // one label (a serial scan of every leaf voxel with its six neighbours took about a tenth of
    // the extraction on the shared mandible); both voxels of each edge, sorted, took 1.4 s more.
    std::vector<LabelEdge> found;
    if (!givenEdges) found = findLabelEdges(labels);
    const std::vector<LabelEdge>& edges = givenEdges ? *givenEdges : found;
    std::vector<Coord> starts;
    starts.reserve(edges.size());
    for (const LabelEdge& e : edges)  // sorted by voxel, then axis
        if (starts.empty() || starts.back() != e.voxel) starts.push_back(e.voxel);

    // Chunks of starts in parallel, each with its own marks: a component is found by the first
    // chunk that holds one of its starts, at its smallest start, as a serial scan finds it (the
    // serial scan was 3.7 s of the shared mandible's extraction); later chunks' copies are dropped.
    constexpr std::size_t kChunk = 1 << 16;
    std::vector<ChunkComponents> chunks((starts.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t c) {
        const std::size_t lo = c * kChunk, hi = std::min(starts.size(), lo + kChunk);
        chunks[c] = findSmallComponents(labels, starts.data() + lo, starts.data() + hi, maxOutsideVoxels, maxRegionVoxels);
    });
    std::vector<SmallComponent> small;
    std::set<Label> hasLarge;
    std::set<Coord> foundAt;  // each component's smallest voxel
    for (ChunkComponents& chunk : chunks) {
        hasLarge.insert(chunk.hasLarge.begin(), chunk.hasLarge.end());
        for (SmallComponent& comp : chunk.small)
            if (foundAt.insert(*std::min_element(comp.voxels.begin(), comp.voxels.end())).second)
                small.push_back(std::move(comp));
    }
    // A region made only of small components keeps its largest (the first found among equals).
    std::map<Label, std::size_t> keep;
    for (std::size_t i = 0; i < small.size(); ++i) {
        const Label L = small[i].label;
        if (L == kOutsideLabel || hasLarge.count(L)) continue;
        const auto it = keep.find(L);
        if (it == keep.end() || small[i].voxels.size() > small[it->second].voxels.size()) keep[L] = i;
    }
    SmallComponentStats stats;
    auto write = labels.getAccessor();
    for (std::size_t i = 0; i < small.size(); ++i) {
        const SmallComponent& s = small[i];
        const auto k = keep.find(s.label);
        if (k != keep.end() && k->second == i) continue;
        for (const Coord& c : s.voxels) write.setValueOn(c, s.fill);
        if (relabelled) relabelled->insert(relabelled->end(), s.voxels.begin(), s.voxels.end());
        if (s.label == kOutsideLabel) {
            ++stats.pockets;
            stats.pocketVoxels += s.voxels.size();
        } else {
            ++stats.fragments;
            stats.fragmentVoxels += s.voxels.size();
        }
    }
    return stats;
}

}  // namespace jawmesh
