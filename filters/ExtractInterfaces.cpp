// Implements filters/ExtractInterfaces.h; what it computes, its rules and its contract are documented there.
#include "filters/ExtractInterfaces.h"

#include "filters/AdaptiveCells.h"
#include "filters/DualQuads.h"
#include "filters/LabelEdges.h"
#include "filters/RegionSeeds.h"
#include "filters/SmallComponents.h"
#include "filters/WellComposedLabels.h"
#include "io/Error.h"
#include "io/ResourceUsage.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

namespace jawmesh {
namespace {

using openvdb::Coord;

// Signed distances of the regions at voxel centres (mm); 0 stands for "no field".
class Fields {
public:
    explicit Fields(const std::map<Label, openvdb::FloatGrid::Ptr>& d) {
        for (const auto& [L, g] : d)
            if (g) acc_.emplace(L, g->getConstAccessor());
    }
    /// Parameter t in [0, 1] of the a|b interface along p -> q (lab(p) = a, lab(q) = b).
    double crossing(Label a, Label b, const Coord& p, const Coord& q) const {
        // Each field looked up once per crossing: eight map look-ups per crossing were most of
        // placing the mandible's 13 M vertices.
        const Accessor* fa = a != kOutsideLabel ? field(a) : nullptr;
        const Accessor* fb = b != kOutsideLabel ? field(b) : nullptr;
        const auto phi = [&](const Coord& x) -> double {
            if (fa && fb) return double(fa->getValue(x)) - double(fb->getValue(x));
            if (fa) return 2.0 * double(fa->getValue(x));
            if (fb) return -2.0 * double(fb->getValue(x));
            return 0.0;
        };
        const double fp = phi(p), fq = phi(q);
        // a voxel centre exactly on the interface (distance 0) belongs to the outer side
        if (!(fp <= 0.0 && fq >= 0.0 && fp < fq)) return 0.5;  // fields disagree (repaired voxel)
        return std::clamp(fp / (fp - fq), 0.0, 1.0);
    }

private:
    using Accessor = openvdb::FloatGrid::ConstAccessor;
    const Accessor* field(Label L) const {
        const auto it = acc_.find(L);
        return it == acc_.end() ? nullptr : &it->second;
    }
    std::map<Label, Accessor> acc_;
};

constexpr int kCellEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                   {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

}  // namespace

namespace {

/// Repairs and absorbs in `labels` (field.labels or a copy of it) as labelsToExtract describes;
/// returns the label edges of the result. The edges are found once and then only looked at again
/// around what each step relabels (three searches were 5 s of the shared mandible's extraction).
std::vector<LabelEdge> prepareLabels(openvdb::Int32Grid& labels, const LabelField& field, const ExtractOptions& options,
                                     Progress& progress, ExtractStats* stats) {
    const double voxelMm = labels.voxelSize()[0];
    const auto voxels = [&](double mm3) { return std::size_t(std::max(0.0, mm3) / (voxelMm * voxelMm * voxelMm)); };
    const std::size_t maxPocketVoxels = voxels(options.maxEnclosedOutsideMm3);
    const std::size_t maxFragmentVoxels = voxels(options.maxFragmentMm3);
    ExtractStats local;
    ExtractStats& st = stats ? *stats : local;
    std::vector<LabelEdge> edges = findLabelEdges(labels);
    std::vector<Coord> relabelled, repaired;
    const auto absorb = [&] {
        relabelled.clear();
        const SmallComponentStats f =
            absorbSmallComponents(labels, maxPocketVoxels, maxFragmentVoxels, &relabelled, &edges);
        updateLabelEdges(edges, labels, relabelled);
        st.pocketsFilled += f.pockets;
        st.pocketVoxelsFilled += f.pocketVoxels;
        st.fragmentsAbsorbed += f.fragments;
        st.fragmentVoxelsAbsorbed += f.fragmentVoxels;
        return f.pockets + f.fragments;
    };
    const bool absorbing = maxPocketVoxels > 0 || maxFragmentVoxels > 0;
    if (options.repairDiagonalContacts) {
        // Repair first: a sheet one voxel thin on a diagonal is all fragments until joined. The
        // repair raises voxels to higher-priority regions, which can close pockets and cut off
        // fragments, and absorbing can leave diagonal contacts (only around what it relabelled):
        // alternate until stable.
        makeLabelsWellComposed(labels, field.distances, edges, progress, &repaired);
        updateLabelEdges(edges, labels, repaired);
        for (int round = 0; absorbing && round < 4; ++round) {
            if (absorb() == 0) break;
            repaired.clear();
            const std::size_t n = makeLabelsWellComposed(labels, field.distances, progress, &relabelled, &repaired);
            updateLabelEdges(edges, labels, repaired);
            if (n == 0) break;
        }
    } else {
        if (absorbing) absorb();
        if (countCriticalCells(labels, field.distances) > 0)
            throw Error("interface extraction: the label field has diagonal-only contacts");
    }
    return edges;
}

}  // namespace

openvdb::Int32Grid::Ptr labelsToExtract(const LabelField& field, const ExtractOptions& options, Progress& progress,
                                        ExtractStats* stats) {
    if (!field.labels) throw Error("interface extraction: the label field has no label grid");
    openvdb::Int32Grid::Ptr labels = field.labels->deepCopy();
    prepareLabels(*labels, field, options, progress, stats);
    return labels;
}

InterfaceComplex extractInterfaces(const LabelField& field, const ExtractOptions& options, Progress& progress,
                                   ExtractStats* stats) {
    return extractInterfaces(LabelField(field), options, progress, stats);  // shares the grids: they are copied
}

InterfaceComplex extractInterfaces(LabelField&& field, const ExtractOptions& options, Progress& progress,
                                   ExtractStats* stats) {
    if (!field.labels) throw Error("interface extraction: the label field has no label grid");
    if (!field.labels->transform().isLinear())
        throw Error("interface extraction: the label grid's transform is not linear");
    ProgressStage stage(progress, "interface extraction");

    // Prepared in place when nothing else holds the grid (a copy is ~0.3 GB on the mandible).
    openvdb::Int32Grid::Ptr labels = field.labels.use_count() == 1 ? field.labels : field.labels->deepCopy();
    field.labels.reset();
    std::vector<LabelEdge> edges = prepareLabels(*labels, field, options, progress, stats);
    stage.update(0.3);
    const std::vector<Coord> cells = dualCellsOf(edges);
    returnFreedMemory();  // the repair's and the cell masks' grid leaves, before the big arrays
    progress.checkCancelled();
    stage.update(0.4);

    const auto& xform = labels->transform();
    const openvdb::Mat3d jac = xform.baseMap()->getAffineMap()->getMat4().getMat3();
    const bool mirrored = jac.det() < 0.0;
    const double lo = std::clamp(options.cellMargin, 0.0, 0.5), hi = 1.0 - lo;

    InterfaceComplex out;
    out.surface.vertices.resize(cells.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 1024), [&](const auto& r) {
        progress.checkCancelled();
        auto acc = labels->getConstAccessor();
        const Fields fields(field.distances);
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            std::array<Label, 8> lab;
            for (int k = 0; k < 8; ++k) lab[k] = acc.getValue(dualCellCorner(cells[i], k));
            openvdb::Vec3d sum(0.0);
            int n = 0;
            for (const auto& e : kCellEdges) {
                if (lab[e[0]] == lab[e[1]]) continue;
                const Coord p = dualCellCorner(cells[i], e[0]), q = dualCellCorner(cells[i], e[1]);
                const double t = fields.crossing(lab[e[0]], lab[e[1]], p, q);
                sum += p.asVec3d() + t * (q - p).asVec3d();
                ++n;
            }
            openvdb::Vec3d x = n > 0 ? sum / double(n) : cells[i].asVec3d() + openvdb::Vec3d(0.5);
            for (int a = 0; a < 3; ++a) x[a] = std::clamp(x[a], cells[i][a] + lo, cells[i][a] + hi);
            const auto w = xform.indexToWorld(x);
            out.surface.vertices[i] = Vec3(w.x(), w.y(), w.z());
        }
    });
    stage.update(0.6);
    // The distances placed the vertices; only the seeds need them again.
    if (!options.findSeeds) {
        field.distances.clear();
        returnFreedMemory();  // their leaves' pages, before the quads and blocks are allocated
    }

    const std::vector<DualQuad> quads = dualQuadsOf(edges, cells, *labels, mirrored);
    std::vector<LabelEdge>().swap(edges);  // 16 bytes per quad, not needed from here on
    stage.update(0.65);
    AdaptiveSurface adaptive =
        adaptiveSurface(*labels, cells, quads, out.surface.vertices, options.adaptive, progress,
                        stats ? &stats->adaptive : nullptr);
    // The dual cells that are corners first, then the carried ones, each in cell order.
    std::vector<std::int32_t> vertexId(cells.size(), -1);
    for (const Tri& t : adaptive.triangles)
        for (std::int32_t c : t) vertexId[std::size_t(c)] = -2;
    for (const auto& carried : adaptive.carried)
        for (std::int32_t c : carried) vertexId[std::size_t(c)] = -3;
    // Numbered in one pass, then copied in parallel: most cells are carried, and a vector grown to
    // 13 M vertices (0.3 GB) copied itself and faulted in fresh pages at every doubling.
    const std::size_t corners = std::size_t(std::count(vertexId.begin(), vertexId.end(), -2));
    std::size_t nextCorner = 0, nextCarried = corners;
    for (std::int32_t& id : vertexId)
        if (id == -2) id = std::int32_t(nextCorner++);
        else if (id == -3) id = std::int32_t(nextCarried++);
    std::vector<Vec3> vertices(nextCarried);
    out.sampleErrorMm.resize(corners);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 1 << 14), [&](const auto& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) {
            const std::int32_t id = vertexId[c];
            if (id < 0) continue;
            vertices[std::size_t(id)] = out.surface.vertices[c];
            if (std::size_t(id) < corners) out.sampleErrorMm[std::size_t(id)] = adaptive.sampleErrorMm[c];
        }
    });
    out.surface.vertices = std::move(vertices);
    for (Tri& t : adaptive.triangles)
        for (std::int32_t& c : t) c = vertexId[std::size_t(c)];
    for (auto& carried : adaptive.carried)
        for (std::int32_t& c : carried) c = vertexId[std::size_t(c)];
    out.surface.triangles = std::move(adaptive.triangles);
    out.sides = std::move(adaptive.sides);
    out.carried = std::move(adaptive.carried);
    stage.update(0.8);
    if (options.findSeeds) out.seeds = findRegionSeeds(*labels, field.distances, progress);
    return out;
}

nlohmann::json toJson(const ExtractStats& stats) {
    return {{"enclosed_outside_pockets_filled", {{"pockets", stats.pocketsFilled}, {"voxels", stats.pocketVoxelsFilled}}},
            {"region_fragments_absorbed", {{"fragments", stats.fragmentsAbsorbed}, {"voxels", stats.fragmentVoxelsAbsorbed}}},
            {"adaptive", toJson(stats.adaptive)}};
}

}  // namespace jawmesh
