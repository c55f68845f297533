#include "filters/FillEnclosedOutside.h"

#include <map>
#include <vector>

namespace jawmesh {

EnclosedOutsideStats fillEnclosedOutside(openvdb::Int32Grid& labels, std::size_t maxVoxels) {
    using openvdb::Coord;
    static const Coord kFace[6] = {Coord(1, 0, 0),  Coord(-1, 0, 0), Coord(0, 1, 0),
                                   Coord(0, -1, 0), Coord(0, 0, 1),  Coord(0, 0, -1)};
    // Outside voxels next to a region: where every enclosed pocket has a voxel.
    std::vector<Coord> starts;
    {
        auto acc = labels.getConstAccessor();
        for (auto leaf = labels.tree().cbeginLeaf(); leaf; ++leaf)
            for (auto it = leaf->cbeginValueAll(); it; ++it) {
                if (*it == kOutsideLabel) continue;
                for (const Coord& d : kFace)
                    if (acc.getValue(it.getCoord() + d) == kOutsideLabel) starts.push_back(it.getCoord() + d);
            }
    }
    // 1 = reached by a flood that grew past maxVoxels (connected to the big outside), 2 = pocket.
    openvdb::Int32Grid seen(0);
    auto seenAcc = seen.getAccessor();
    auto acc = labels.getAccessor();
    EnclosedOutsideStats stats;
    std::vector<Coord> component, queue;
    std::vector<std::pair<Coord, Label>> fills;
    for (const Coord& start : starts) {
        if (seenAcc.getValue(start) != 0) continue;
        component.assign(1, start);
        seenAcc.setValue(start, 3);  // in the current flood
        bool open = false;
        for (std::size_t i = 0; i < component.size() && !open; ++i)
            for (const Coord& d : kFace) {
                const Coord n = component[i] + d;
                if (acc.getValue(n) != kOutsideLabel) continue;
                const int s = seenAcc.getValue(n);
                if (s == 1 || (s == 0 && component.size() >= maxVoxels)) {
                    open = true;
                    break;
                }
                if (s != 0) continue;
                seenAcc.setValue(n, 3);
                component.push_back(n);
            }
        for (const Coord& c : component) seenAcc.setValue(c, open ? 1 : 2);
        if (open) continue;
        std::map<Label, std::size_t> around;
        for (const Coord& c : component)
            for (const Coord& d : kFace) {
                const Label L = acc.getValue(c + d);
                if (L != kOutsideLabel) ++around[L];
            }
        Label fill = kOutsideLabel;
        std::size_t most = 0;
        for (const auto& [L, n] : around)  // ascending labels: ties keep the smaller
            if (n > most) {
                most = n;
                fill = L;
            }
        for (const Coord& c : component) fills.emplace_back(c, fill);
        ++stats.pockets;
        stats.voxels += component.size();
    }
    for (const auto& [c, L] : fills) acc.setValueOn(c, L);
    return stats;
}

}  // namespace jawmesh
