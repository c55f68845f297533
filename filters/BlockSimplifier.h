// The serial simplification of one block (SimplifyInterfaces.h, SimplifyPasses.h): a queue of
// edge collapses, cheapest first by quadric cost, each made only when CollapseCheck.h passes it.
// Internal to the simplification.
#pragma once

#include "filters/BlockMesh.h"
#include "filters/CollapseCheck.h"
#include "io/Progress.h"

#include <cstdint>
#include <queue>
#include <utility>
#include <vector>

namespace jawmesh::simplify {

/// Serial simplification of one block. Vertices on the block border are frozen (BlockMesh.h).
/// Writes err and quadrics of the block's own vertices straight into `state` (no other block
/// touches them); everything else comes back in the BlockResult.
class BlockSimplifier {
public:
    BlockSimplifier(State& state, const Block& block, const std::vector<char>& border, const SimplifyOptions& options);

    /// Collapses until no vertex has a collapse that passes every check. Throws Cancelled.
    void run(Progress& progress);
    /// The block's triangles in input vertex ids; also writes its vertices' quadrics back.
    BlockResult result();

private:
    struct Candidate {
        double cost;
        std::int32_t u, v;
        std::uint32_t stamp;
        bool operator<(const Candidate& o) const {  // priority_queue pops the largest: invert
            if (cost != o.cost) return cost > o.cost;
            if (u != o.u) return u > o.u;
            return v > o.v;
        }
    };

    double collapseCost(std::int32_t u, std::int32_t v) const;
    void schedule(std::int32_t u, bool afterRefusal = false);

    BlockMesh mesh_;
    CollapseCheck check_;
    std::vector<std::uint32_t> stamp_;  ///< per local vertex: bumped when its candidate is stale
    /// per local vertex: the neighbours its collapse was refused toward since its neighbourhood
    /// last changed (not queued again until it does)
    std::vector<std::vector<std::int32_t>> refused_;
    std::priority_queue<Candidate> heap_;
    std::size_t collapses_ = 0;
    std::vector<std::int32_t> touchedFrozen_;  ///< input ids, with repeats until result()
    // scratch buffers
    std::vector<std::int32_t> ring_, cand_;
    std::vector<std::pair<double, std::int32_t>> costs_;
    CollapsePlan plan_;
};

}  // namespace jawmesh::simplify
