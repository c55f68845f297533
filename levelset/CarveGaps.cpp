// Implements levelset/CarveGaps.h; what it computes, its rules and its contract are documented there.
#include "levelset/CarveGaps.h"

#include "io/Error.h"
#include "io/ParallelInOrder.h"
#include "io/ResourceUsage.h"
#include "levelset/CarveMeasure.h"
#include "levelset/CarveRules.h"
#include "levelset/Csg.h"

#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <utility>

namespace jawmesh {

double pdlThicknessAt(const PdlProfile& p, double s) {
    s = std::clamp(s, 0.0, 1.0);
    return s < 0.5 ? p.cervical + (p.midRoot - p.cervical) * (s / 0.5) : p.midRoot + (p.apical - p.midRoot) * ((s - 0.5) / 0.5);
}

namespace {

using namespace carve;
/// What one tooth's rules say at one voxel (before the clearance between teeth).
struct Local {
    double T = 0;      ///< tooth distance
    double tooth = 0;  ///< carved tooth field
    double pdl = 0;    ///< PDL field
    double fill = 0;   ///< bridged-gap field (negative: gap that becomes socket)
    double excl = 0;   ///< w - T: positive where bone is excluded by this tooth
};

/// The PDL's faces where a bridged gap is wide or the root overlaps the bone (g = T + B; e, w: the
/// root's erosion and the socket's widening, updated).
void movePdlForGapOrOverlap(const CarveRules& rules, double g, double gap, double th, double& e, double& w) {
    // A bridged gap wider than w + boneShiftMax: the PDL moves out to meet the bone where it
    // has moved boneShiftMax, eroding the root less (and, past that, the PDL thickens).
    if (gap < 0 && g - w > rules.boneShiftMax) {
        w = g - rules.boneShiftMax;
        e = std::max(0.0, th - w);
    }
    // The root overlapping the bone by more than boneShiftMax - w (g < 0): the bone surface
    // moves boneShiftMax, the PDL thins (down to kMinPdlShare of t, past which the bone
    // moves farther); the root keeps its erosion e.
    else if (gap < 0 && w - g > rules.boneShiftMax)
        w = std::max(g + rules.boneShiftMax, kMinPdlShare * th - e);
}

Local evalLocal(const ToothWork& t, const CarveRules& rules, FloatAcc& T, FloatAcc& X, FloatAcc& B,
                const openvdb::math::Transform& xf, const Coord& c) {
    Local r;
    r.T = T.getValue(c);
    const double b = signedBone(B, X, rules, c);
    const double h = heightOf(t, xf.indexToWorld(c));
    const double th = thicknessAt(t, h);
    double e = rules.ratio * th * erosionShare(t, rules, h), w = th - e;
    const double g = r.T + b;  // root-socket gap where the surfaces face each other (file comment)
    double gap = g - rules.gapBridge;
    if (gap < 0) {
        const Coord dx(1, 0, 0), dy(0, 1, 0), dz(0, 0, 1);
        const Vec3d gT(T.getValue(c + dx) - T.getValue(c - dx), T.getValue(c + dy) - T.getValue(c - dy),
                       T.getValue(c + dz) - T.getValue(c - dz));
        const Vec3d gB(signedBone(B, X, rules, c + dx) - signedBone(B, X, rules, c - dx),
                       signedBone(B, X, rules, c + dy) - signedBone(B, X, rules, c - dy),
                       signedBone(B, X, rules, c + dz) - signedBone(B, X, rules, c - dz));
        const double lT = gT.length(), lB = gB.length();
        // A clamped field (outside its band) has no direction: treat as not facing.
        const bool bKnown = boneKnown(B, X, c + dx) && boneKnown(B, X, c - dx) && boneKnown(B, X, c + dy) &&
                            boneKnown(B, X, c - dy) && boneKnown(B, X, c + dz) && boneKnown(B, X, c - dz);
        const double dot = (bKnown && lT > 1e-3 * rules.voxel && lB > 1e-3 * rules.voxel) ? gT.dot(gB) / (lT * lB) : 0.0;
        const bool belowCrest = rules.pdlKept && t.hasRoot && h < t.hCervical - kKeptPdlCrestBandMm;
        gap = std::max(gap, (dot + (belowCrest ? rules.rootFacingCos : rules.facingCos)) * rules.gapBridge);
        // An implant has no PDL to move: its gaps become bone, its overlaps are its own.
        if (!t.implant) movePdlForGapOrOverlap(rules, g, gap, th, e, w);
    }
    const double socket = std::min(b - std::max(e, rules.minCapRise), gap);  // < 0: in the socket of this tooth
    // Exact ties (input bands sampled exactly at T = -e, T = w or on the cap) must land in exactly
    // one region, or they leave a void: the tooth takes T = -e and the cap, the bone takes T = w.
    r.tooth = std::max(r.T, std::min(below(r.T + e), below(-socket)));
    r.pdl = std::max({r.T - w, -(r.T + e), socket});
    r.fill = std::max(-r.T, gap);
    r.excl = below(w - r.T);
    return r;
}

/// Accessors of one thread to every tooth's grids.
struct Accessors {
    std::vector<FloatAcc> T, X;
    FloatAcc B;
    Accessors(const std::vector<ToothWork>& teeth, const FloatGrid& bone) : B(bone.getConstAccessor()) {
        for (const auto& t : teeth) {
            T.push_back(t.T->getConstAccessor());
            X.push_back(t.X->getConstAccessor());
        }
    }
};

/// Teeth whose bounds touch the given index box.
std::vector<int> candidates(const std::vector<ToothWork>& teeth, const CoordBBox& box) {
    std::vector<int> out;
    for (int i = 0; i < int(teeth.size()); ++i)
        if (teeth[i].box.hasOverlap(box)) out.push_back(i);
    return out;
}

/// Bisector clearance field of tooth k against the other candidates (negative: k may own c).
double bisector(int k, const std::vector<int>& cand, Accessors& acc, const Coord& c, double clearance) {
    double v = -std::numeric_limits<double>::infinity();
    const double tk = acc.T[k].getValue(c);
    for (int m : cand)
        if (m != k) v = std::max(v, 0.5 * (tk - acc.T[m].getValue(c) + clearance));
    return v;
}

void validate(const CarveOptions& o, const FloatGrid& bone, const std::map<int, FloatGrid::ConstPtr>& teeth) {
    if (!(o.pdlRatio >= 0 && o.pdlRatio <= 1)) throw Error("carve: --pdl-ratio must be in [0, 1]");
    if (!(o.clearanceVoxels >= 0)) throw Error("carve: clearance must be >= 0 voxels");
    if (!(o.gapBridgeMm >= 0)) throw Error("carve: gap bridge must be >= 0 mm");
    if (!(o.boneShiftMaxMm >= 0)) throw Error("carve: bone shift must be >= 0 mm");
    if (!(o.apexTaperMm >= 0)) throw Error("carve: apex taper must be >= 0 mm");
    if (!(o.gapFacingDeg >= 90 && o.gapFacingDeg <= 180)) throw Error("carve: the gap facing angle must be in [90, 180] degrees");
    if (!(o.minCapRiseMm >= 0)) throw Error("carve: the cap rise must be >= 0 mm");
    const double tMin = thicknessRangeMm(o).first;
    if (!(tMin > 0)) throw Error("carve: PDL thickness must be > 0 mm");
    const double voxel = uniformVoxelSizeMm(bone);
    bandHalfWidthMm(bone);
    if (tMin < 2 * voxel) {
        std::ostringstream s;
        s << "carve: PDL thickness " << tMin << " mm is under 2 voxels of " << voxel
          << " mm; use a smaller voxel size (at least 4 voxels across are recommended)";
        throw Error(s.str());
    }
    for (const auto& [unn, grid] : teeth) {
        toothLabel(unn);
        if (o.implants.count(unn)) implantLabel(unn);
        if (!grid) throw Error("carve: tooth " + std::to_string(unn) + " has no grid");
        requireSameTransform(bone, *grid, "carve");
        bandHalfWidthMm(*grid);
    }
}

/// What the phases of carveJaw share: the inputs, the rules, the teeth's working fields, the
/// voxels near teeth and what is built (the field, the summary).
struct CarveContext {
    const FloatGrid& bone;
    const CarveOptions& options;
    Progress& progress;
    CarveSummary& summary;
    CarveRules rules;
    Label boneL = 0;
    std::vector<ToothWork> teeth;
    openvdb::MaskTree nearMask;                    ///< union of the teeth's bands
    std::unique_ptr<openvdb::Int32Tree> nearLabels;  ///< label of every voxel near a tooth
    std::unique_ptr<openvdb::FloatTree> nearBone;    ///< carved bone distance there
    std::unique_ptr<openvdb::tree::LeafManager<openvdb::Int32Tree>> nearLeaves;
    LabelField field;
    FloatGrid::Ptr boneOut;  ///< the bone's distance grid, carved near the teeth
    std::chrono::steady_clock::time_point lastLap;

    CarveContext(const FloatGrid& b, const CarveOptions& o, Progress& pr, CarveSummary& s, std::chrono::steady_clock::time_point start)
        : bone(b), options(o), progress(pr), summary(s), lastLap(start) {}
    const openvdb::math::Transform& xf() const { return bone.transform(); }
    /// Records the phase just finished: wall seconds since the last lap, peak memory so far.
    void lap(const char* name) {
        const auto now = std::chrono::steady_clock::now();
        summary.stages.push_back({name, std::chrono::duration<double>(now - lastLap).count(), peakResidentMemoryBytes()});
        lastLap = now;
    }
};

/// The rules' parameters (mm) from the options and the bone's voxel size.
CarveRules rulesOf(const CarveOptions& options, const FloatGrid& bone) {
    CarveRules rules;
    rules.voxel = uniformVoxelSizeMm(bone);
    rules.ratio = options.pdlRatio;
    rules.uniformThickness = options.profile ? options.profile->midRoot : options.pdlThicknessMm;
    rules.profile = options.profile;
    rules.gapBridge = options.gapBridgeMm;
    rules.boneShiftMax = options.boneShiftMaxMm;
    rules.apexTaper = options.apexTaperMm;
    rules.facingCos = -std::cos(options.gapFacingDeg * M_PI / 180.0);
    rules.minCapRise = options.minCapRiseMm;
    rules.pdlKept = options.pdlKept;
    rules.rootFacingCos = -std::cos(kKeptPdlRootFacingDeg * M_PI / 180.0);
    rules.clearance = options.clearanceVoxels * rules.voxel;
    rules.maxThickness = thicknessRangeMm(options).second;
    const double eMax = rules.ratio * rules.maxThickness;
    rules.far = rules.gapBridge + eMax + 2 * rules.voxel;
    return rules;
}

/// A tooth's own PDL: the jaw's, or its entry in CarveOptions::toothPdl.
void setOwnPdl(ToothWork& t, const CarveRules& rules, const CarveOptions& options) {
    t.profile = rules.profile;
    t.uniformThickness = rules.uniformThickness;
    if (t.implant) {  // fused: no erosion, no widening, gaps bridged into bone
        t.profile.reset();
        t.uniformThickness = 0;
        return;
    }
    if (const auto own = options.toothPdl.find(t.unn); own != options.toothPdl.end()) {
        const PdlProfile& p = own->second;
        const bool uniform = p.cervical == p.midRoot && p.apical == p.midRoot;
        t.profile = uniform ? std::nullopt : std::optional(p);
        t.uniformThickness = p.midRoot;
    }
}

/// Band half widths (voxels; outside, inside) for a socket widening w, an erosion e and the
/// clearance, mm: the PDL rules read the tooth's distance that far on each side.
std::pair<double, double> bandHalfWidthsVoxels(double wMm, double eMm, double clearanceMm, double voxelMm) {
    return {std::max(1.0, std::ceil((wMm + clearanceMm) / voxelMm - 1e-9)), std::max(1.0, std::ceil(eMm / voxelMm - 1e-9))};
}

/// Band half widths (voxels) tooth i needs: its erosion inside; outside, the socket widening plus
/// the clearance of itself and of every tooth near it (their bisectors read its distances), so
/// a thicker PDL on one tooth widens only its own and its neighbours' bands.
std::pair<double, double> bandVoxels(const std::vector<ToothWork>& teeth, const std::vector<CoordBBox>& boxes,
                                     std::size_t i, const CarveRules& rules) {
    const auto widening = [&](const ToothWork& t) {
        const double tMax = thicknessRangeMm(t.profile, t.uniformThickness).second;
        return tMax - rules.ratio * tMax;
    };
    double w = widening(teeth[i]);
    const int near = int(std::ceil(1.0 / rules.voxel));  // teeth within 1 mm of each other
    CoordBBox box = boxes[i];
    box.expand(near);
    for (std::size_t m = 0; m < teeth.size(); ++m)
        if (m != i && box.hasOverlap(boxes[m])) w = std::max(w, widening(teeth[m]));
    const double e = rules.ratio * thicknessRangeMm(teeth[i].profile, teeth[i].uniformThickness).second;
    return bandHalfWidthsVoxels(w, e, rules.clearance, rules.voxel);
}

/// Phase 1. Per tooth (in parallel): its band, and tooth / bone distances where a gap can be
/// bridged. The band must hold the PDL rules: e inside, w + clearance outside (for the bisector).
void prepareTeeth(CarveContext& ctx, const std::map<int, FloatGrid::ConstPtr>& teethIn) {
    const CarveRules& rules = ctx.rules;
    std::vector<std::pair<int, FloatGrid::ConstPtr>> in(teethIn.begin(), teethIn.end());
    ctx.teeth.resize(teethIn.size());
    std::vector<CoordBBox> boxes;
    for (std::size_t i = 0; i < in.size(); ++i) {
        ToothWork& t = ctx.teeth[i];
        t.unn = in[i].first;
        t.implant = ctx.options.implants.count(t.unn) > 0;
        t.toothL = t.implant ? implantLabel(t.unn) : toothLabel(t.unn);
        t.pdlL = pdlLabel(t.unn);
        setOwnPdl(t, rules, ctx.options);
        boxes.push_back(in[i].second->evalActiveVoxelBoundingBox());
    }
    ProgressStage stage(ctx.progress, "carve: tooth bands");
    parallelForFirstErrorInOrder(in.size(), ctx.progress, [&](std::size_t i) {
        const auto [exVoxels, inVoxels] = bandVoxels(ctx.teeth, boxes, i, rules);
        prepareTooth(ctx.teeth[i], *in[i].second, ctx.bone, rules, exVoxels, inVoxels, ctx.options);
    });
}

/// The label of voxel c near the candidate teeth `cand` and its carved bone distance: bone where
/// the bone field (bridged gaps in, what the teeth exclude out) is negative, unless a tooth and
/// then a PDL claims it on its side of the bisectors (UNN order breaks exact ties).
std::pair<Label, double> labelVoxel(const CarveContext& ctx, Accessors& acc, const std::vector<int>& cand,
                                    std::vector<Local>& loc, const Coord& c) {
    const CarveRules& rules = ctx.rules;
    double excl = -std::numeric_limits<double>::infinity();
    double fill = std::numeric_limits<double>::infinity();
    float bIn;
    double bAll = (acc.B.probeValue(c, bIn) || bIn < 0) ? double(bIn) : rules.far;
    for (int k : cand) {
        loc[k] = evalLocal(ctx.teeth[k], rules, acc.T[k], acc.X[k], acc.B, ctx.xf(), c);
        excl = std::max(excl, loc[k].excl);
        fill = std::min(fill, loc[k].fill);
        float x;
        if (acc.X[k].probeValue(c, x)) bAll = std::min(bAll, double(x));
    }
    const double b = std::max(std::min(bAll, fill), excl);
    for (int k : cand)  // teeth first, then PDLs
        if (std::max(loc[k].tooth, bisector(k, cand, acc, c, rules.clearance)) < 0) return {ctx.teeth[k].toothL, b};
    for (int k : cand)
        if (std::max(loc[k].pdl, bisector(k, cand, acc, c, rules.clearance)) < 0) return {ctx.teeth[k].pdlL, b};
    return {b < 0 ? ctx.boneL : kOutsideLabel, b};
}

/// Phase 2. Labels and bone distance of every voxel near a tooth, in parallel over leaves.
void labelVoxelsNearTeeth(CarveContext& ctx) {
    for (const auto& t : ctx.teeth) ctx.nearMask.topologyUnion(t.T->tree());
    ctx.nearLabels = std::make_unique<openvdb::Int32Tree>(ctx.nearMask, kOutsideLabel, kOutsideLabel, openvdb::TopologyCopy());
    const float boneBg = ctx.bone.background();
    ctx.nearBone = std::make_unique<openvdb::FloatTree>(ctx.nearMask, boneBg, boneBg, openvdb::TopologyCopy());
    ctx.nearLeaves = std::make_unique<openvdb::tree::LeafManager<openvdb::Int32Tree>>(*ctx.nearLabels);
    ProgressStage stage(ctx.progress, "carve: label voxels near teeth");
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ctx.nearLeaves->leafCount()), [&](const tbb::blocked_range<std::size_t>& r) {
        if (ctx.progress.cancelled()) return;
        Accessors acc(ctx.teeth, ctx.bone);
        std::vector<Local> loc(ctx.teeth.size());
        for (std::size_t li = r.begin(); li != r.end(); ++li) {
            auto& leaf = ctx.nearLeaves->leaf(li);
            auto* boneLeaf = ctx.nearBone->probeLeaf(leaf.origin());
            CoordBBox lb = leaf.getNodeBoundingBox();
            lb.expand(1);
            const auto cand = candidates(ctx.teeth, lb);
            for (auto v = leaf.beginValueOn(); v; ++v) {
                const auto [label, b] = labelVoxel(ctx, acc, cand, loc, v.getCoord());
                v.setValue(label);
                boneLeaf->setValueOnly(v.getCoord(), float(std::clamp(b, -double(boneBg), double(boneBg))));
            }
        }
    });
    ctx.progress.checkCancelled();
}

/// Phase 3. The label grid: bone interior, tooth interiors, then the voxels near teeth; the bone's
/// distance grid with the teeth's interiors taken out and the carved values near them.
void assembleLabels(CarveContext& ctx) {
    ProgressStage stage(ctx.progress, "carve: assemble labels");
    LabelField& field = ctx.field;
    const float boneBg = ctx.bone.background();
    ctx.boneOut = ctx.bone.deepCopy();
    ctx.boneOut->setName(labelName(ctx.boneL));
    const auto boneInside = openvdb::tools::sdfInteriorMask(ctx.bone);
    field.labels = openvdb::Int32Grid::create(kOutsideLabel);
    field.labels->setTree(std::make_shared<openvdb::Int32Tree>(boneInside->tree(), kOutsideLabel, ctx.boneL, openvdb::TopologyCopy()));
    field.labels->setTransform(ctx.xf().copy());
    field.labels->setName("labels");
    auto& lt = field.labels->tree();
    auto& bt = ctx.boneOut->tree();
    // Voxel by voxel through accessors (the trees' own calls walked from the root for each of the
    // teeth's millions of interior voxels, half a second on the mandible); a fill clears them.
    auto la = field.labels->getAccessor();
    auto ba = ctx.boneOut->getAccessor();
    const openvdb::tree::ValueAccessor<const openvdb::MaskTree> near(ctx.nearMask);
    for (const auto& t : ctx.teeth) {
        ctx.progress.checkCancelled();
        const auto inside = openvdb::tools::sdfInteriorMask(*t.T);
        for (auto it = inside->tree().cbeginValueOn(); it; ++it) {
            if (it.isTileValue()) {
                lt.fill(it.getBoundingBox(), t.toothL, true);
                bt.fill(it.getBoundingBox(), boneBg, false);
            } else if (!near.isValueOn(it.getCoord())) {
                la.setValueOn(it.getCoord(), t.toothL);
                ba.setValueOff(it.getCoord(), boneBg);
            }
        }
    }
    for (auto it = ctx.nearLabels->cbeginLeaf(); it; ++it) {
        auto* L = lt.touchLeaf(it->origin());
        auto* BL = bt.touchLeaf(it->origin());
        const auto* nb = ctx.nearBone->probeConstLeaf(it->origin());
        for (auto v = it->cbeginValueOn(); v; ++v) {
            const auto off = v.pos();
            if (*v == kOutsideLabel) L->setValueOff(off, kOutsideLabel);
            else L->setValueOn(off, *v);
            BL->setValueOn(off, nb->getValue(off));
        }
    }
}

/// The tooth (its index) whose tooth or PDL each label is, -1 for other labels: a table by label
/// value (a few hundred), read 27 times for every voxel near the teeth by the clearance pass, where
/// a map's search was most of its time.
class ToothOfLabel {
public:
    explicit ToothOfLabel(const std::vector<ToothWork>& teeth) {
        for (int k = 0; k < int(teeth.size()); ++k) set(teeth[std::size_t(k)].toothL, k), set(teeth[std::size_t(k)].pdlL, k);
    }
    int operator()(Label l) const { return l >= 0 && std::size_t(l) < tooth_.size() ? tooth_[std::size_t(l)] : -1; }

private:
    void set(Label l, int k) {
        if (std::size_t(l) >= tooth_.size()) tooth_.resize(std::size_t(l) + 1, -1);
        tooth_[std::size_t(l)] = k;
    }
    std::vector<int> tooth_;
};

/// Whether voxel p of tooth `a`'s tooth or PDL gives way to a 26-neighbour of another tooth's
/// (the one with the smaller margin to the bisector; UNN order on ties); counts a tooth voxel
/// touching bone in touchesBone.
bool dropForClearance(const CarveContext& ctx, Accessors& acc, const openvdb::Int32Grid::ConstAccessor& la,
                      const ToothOfLabel& ownerOf, const Coord& p, Label l, int a, bool& touchesBone) {
    const auto& teeth = ctx.teeth;
    touchesBone = false;
    for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
                const Coord q = p.offsetBy(dx, dy, dz);
                const Label m = la.getValue(q);
                if (m == ctx.boneL && l == teeth[a].toothL && !teeth[a].implant) touchesBone = true;
                const int b = ownerOf(m);
                if (b < 0 || b == a) continue;
                const double marginP = acc.T[b].getValue(p) - acc.T[a].getValue(p);
                const double marginQ = acc.T[a].getValue(q) - acc.T[b].getValue(q);
                if (marginP < marginQ || (marginP == marginQ && teeth[a].unn > teeth[b].unn)) return true;
            }
    return false;
}

/// Phase 4. Clearance, discretely: no voxel of one tooth or its PDL 26-touches another tooth's.
void enforceClearance(CarveContext& ctx) {
    ProgressStage stage(ctx.progress, "carve: clearance");
    const ToothOfLabel ownerOf(ctx.teeth);
    const std::size_t leafCount = ctx.nearLeaves->leafCount();
    std::vector<std::vector<Coord>> drops(leafCount);
    std::vector<std::size_t> boneContacts(leafCount, 0);
    const auto& labels = *ctx.field.labels;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leafCount), [&](const tbb::blocked_range<std::size_t>& r) {
        Accessors acc(ctx.teeth, ctx.bone);
        auto la = labels.getConstAccessor();
        for (std::size_t li = r.begin(); li != r.end(); ++li) {
            for (auto v = ctx.nearLeaves->leaf(li).cbeginValueOn(); v; ++v) {
                const Coord p = v.getCoord();
                const Label l = la.getValue(p);
                const int own = ownerOf(l);
                if (own < 0) continue;
                bool touchesBone = false;
                if (dropForClearance(ctx, acc, la, ownerOf, p, l, own, touchesBone)) drops[li].push_back(p);
                else if (touchesBone) ++boneContacts[li];
            }
        }
    });
    auto& lt = ctx.field.labels->tree();
    for (const auto& d : drops)
        for (const auto& p : d) lt.setValueOff(p, kOutsideLabel), ++ctx.summary.clearanceVoxelsRemoved;
    for (auto n : boneContacts) ctx.summary.toothBoneContacts += n;
}

/// Tooth k's tooth and PDL distance grids on its band, consistent with the labels.
void toothAndPdlDistances(CarveContext& ctx, int k) {
    const CarveRules& rules = ctx.rules;
    const auto& t = ctx.teeth[k];
    const auto& xf = ctx.xf();
    auto toothGrid = t.T->deepCopy();
    auto pdlGrid = FloatGrid::create(t.T->background());
    pdlGrid->setTree(std::make_shared<openvdb::FloatTree>(t.T->tree(), t.T->background(), t.T->background(), openvdb::TopologyCopy()));
    pdlGrid->setTransform(xf.copy());
    openvdb::tree::LeafManager<openvdb::FloatTree> tl(toothGrid->tree());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tl.leafCount()), [&](const tbb::blocked_range<std::size_t>& r) {
        Accessors acc(ctx.teeth, ctx.bone);
        auto la = ctx.field.labels->getConstAccessor();
        for (std::size_t li = r.begin(); li != r.end(); ++li) {
            auto& leaf = tl.leaf(li);
            auto* pl = pdlGrid->tree().probeLeaf(leaf.origin());
            CoordBBox lb = leaf.getNodeBoundingBox();
            lb.expand(1);
            const auto cand = candidates(ctx.teeth, lb);
            for (auto v = leaf.beginValueOn(); v; ++v) {
                const Coord c = v.getCoord();
                const Local l = evalLocal(t, rules, acc.T[k], acc.X[k], acc.B, xf, c);
                const double bis = bisector(k, cand, acc, c, rules.clearance);
                // Inside the root a kept PDL (no erosion) is bounded by the root's surface alone: the
                // socket term, a yes/no of the facing test there, raised the field inside the root and
                // pulled the extracted tooth / PDL wall a fifth of a voxel into the PDL (2.8 % of its
                // volume, session 31).
                const double pdlField = rules.pdlKept && l.T < 0 ? -l.T : l.pdl;
                double tooth = std::max(l.tooth, bis), pdl = std::max(pdlField, bis);
                // Voxels dropped by the clearance pass, or won by another tooth on a tie.
                const Label lab = la.getValue(c);
                if (tooth < 0 && lab != t.toothL) tooth = 0.5 * rules.voxel;
                if (pdl < 0 && lab != t.pdlL) pdl = 0.5 * rules.voxel;
                const double bg = t.T->background();
                v.setValue(float(std::clamp(tooth, -bg, bg)));
                pl->setValueOnly(c, float(std::clamp(pdl, -bg, bg)));
            }
        }
    });
    // Deep interior tiles of this tooth that another tooth won (overlapping inputs).
    auto ta = toothGrid->getAccessor();
    auto la = ctx.field.labels->getConstAccessor();
    for (auto leaf = ctx.nearLabels->cbeginLeaf(); leaf; ++leaf) {
        if (!t.box.hasOverlap(leaf->getNodeBoundingBox())) continue;
        for (auto v = leaf->cbeginValueOn(); v; ++v) {
            const Coord c = v.getCoord();
            if (!ta.isValueOn(c) && ta.getValue(c) < 0 && la.getValue(c) != t.toothL) ta.setValueOff(c, float(0.5 * rules.voxel));
        }
    }
    toothGrid->setName(labelName(t.toothL));
    toothGrid->setGridClass(openvdb::GRID_LEVEL_SET);
    pdlGrid->setName(labelName(t.pdlL));
    pdlGrid->setGridClass(openvdb::GRID_LEVEL_SET);
    ctx.field.distances[t.toothL] = toothGrid;
    if (!t.implant) ctx.field.distances[t.pdlL] = pdlGrid;
}

/// Phase 5. Distance grids of every tooth and PDL, and the bone's.
void regionDistances(CarveContext& ctx) {
    ProgressStage stage(ctx.progress, "carve: region distances");
    for (int k = 0; k < int(ctx.teeth.size()); ++k) {
        ctx.progress.checkCancelled();
        toothAndPdlDistances(ctx, k);
    }
    ctx.field.distances[ctx.boneL] = ctx.boneOut;
}

/// Phase 6. Measurements per tooth (levelset/CarveMeasure.h) and warnings.
void measureTeeth(CarveContext& ctx) {
    ProgressStage stage(ctx.progress, "carve: measure");
    CarveSummary& summary = ctx.summary;
    // The teeth at once (each is parallel inside, but its thickness statistics are serial).
    std::vector<ToothCarveSummary> measured(ctx.teeth.size());
    parallelForFirstErrorInOrder(ctx.teeth.size(), ctx.progress, [&](std::size_t i) {
        measured[i].unn = ctx.teeth[i].unn;
        measured[i].implant = ctx.teeth[i].implant;
        measureTooth(ctx.field, measured[i].unn, ctx.options.capExclusionMm, measured[i]);
    });
    for (std::size_t i = 0; i < ctx.teeth.size(); ++i) {
        const ToothWork& t = ctx.teeth[i];
        const ToothCarveSummary& s = measured[i];
        if (s.pdlVolumeMm3 <= 0 && !s.implant)
            summary.warnings.push_back("tooth " + std::to_string(t.unn) + " has no bone contact: no PDL");
        else if (s.impacted)
            summary.warnings.push_back("tooth " + std::to_string(t.unn) + " is fully inside bone: closed PDL envelope");
        if (t.profile && !t.hasRoot)
            summary.warnings.push_back("tooth " + std::to_string(t.unn) +
                                       ": no root found for the thickness profile; uniform mid-root value used");
        summary.teeth.push_back(s);
    }
    if (summary.toothBoneContacts)
        summary.warnings.push_back(std::to_string(summary.toothBoneContacts) +
                                   " tooth voxels touch bone directly (PDL widening under 2 voxels?)");
}

}  // namespace

double toothBandVoxels(const CarveOptions& options, double voxelMm) {
    const double tMax = thicknessRangeMm(options).second;
    const double e = options.pdlRatio * tMax;
    const auto [outside, inside] = bandHalfWidthsVoxels(tMax - e, e, options.clearanceVoxels * voxelMm, voxelMm);
    return std::max(outside, inside);
}

LabelField carveJaw(Jaw jaw, const FloatGrid& bone, const std::map<int, FloatGrid::ConstPtr>& teethIn,
                    const CarveOptions& options, CarveSummary& summary, Progress& progress) {
    const auto start = std::chrono::steady_clock::now();
    validate(options, bone, teethIn);
    summary = CarveSummary();
    CarveContext ctx(bone, options, progress, summary, start);
    ctx.rules = rulesOf(options, bone);
    ctx.boneL = boneLabel(jaw);
    summary.voxelSizeMm = ctx.rules.voxel;
    ctx.field.voxelSizeMm = ctx.rules.voxel;
    ctx.field.jaw = jaw;
    prepareTeeth(ctx, teethIn);
    ctx.lap("tooth bands");
    labelVoxelsNearTeeth(ctx);
    ctx.lap("label voxels near teeth");
    assembleLabels(ctx);
    ctx.lap("assemble labels");
    enforceClearance(ctx);
    ctx.lap("clearance");
    regionDistances(ctx);
    ctx.lap("region distances");
    measureTeeth(ctx);
    ctx.lap("measure");
    summary.seconds = secondsSince(start);
    return std::move(ctx.field);
}

CarveOptions keptPdlCarveOptions(CarveOptions o, double voxelMm) {
    // The overlap rule of evalLocal leaves a PDL of kMinPdlShare * t where the gap is thinner, and
    // with no erosion and no bone shift it keeps every gap between that and t + the bridge.
    o.pdlThicknessMm = kKeptPdlMinVoxels * voxelMm / kMinPdlShare;
    o.profile.reset();
    o.pdlRatio = 0;
    o.boneShiftMaxMm = 0;
    o.gapBridgeMm = std::max(o.gapBridgeMm, kKeptPdlBridgeMm);
    o.gapFacingDeg = kKeptPdlFacingDeg;
    o.minCapRiseMm = kKeptPdlMinVoxels * voxelMm;
    o.pdlKept = true;
    return o;
}

CarveOptions carveOptionsFor(const JawSurfaces& surfaces, CarveOptions options, double voxelMm) {
    if (options.axes.empty()) options.axes = surfaces.axes;
    return surfaces.pdlKept ? keptPdlCarveOptions(std::move(options), voxelMm) : options;
}

nlohmann::json toJson(const CarveOptions& o) {
    nlohmann::json j = {{"pdl_thickness_mm", o.pdlThicknessMm},
                        {"pdl_ratio", o.pdlRatio},
                        {"clearance_voxels", o.clearanceVoxels},
                        {"gap_bridge_mm", o.gapBridgeMm},
                        {"bone_shift_max_mm", o.boneShiftMaxMm},
                        {"gap_facing_deg", o.gapFacingDeg},
                        {"min_cap_rise_mm", o.minCapRiseMm},
                        {"apex_taper_mm", o.apexTaperMm},
                        {"cap_exclusion_mm", o.capExclusionMm},
                        {"pdl", o.pdlKept ? "kept" : "generated"}};
    const auto profileJson = [](const PdlProfile& p) {
        return nlohmann::json{{"cervical", p.cervical}, {"mid_root", p.midRoot}, {"apical", p.apical}};
    };
    if (o.profile) j["pdl_profile_mm"] = profileJson(*o.profile);
    for (const auto& [unn, p] : o.toothPdl) j["tooth_pdl_mm"][std::to_string(unn)] = profileJson(p);
    if (!o.implants.empty()) j["implants"] = o.implants;
    return j;
}

CarveOptions carveOptionsFromJson(const nlohmann::json& j, const std::string& name) {
    const auto profileOf = [](const nlohmann::json& p) {
        return PdlProfile{p.at("cervical").get<double>(), p.at("mid_root").get<double>(), p.at("apical").get<double>()};
    };
    try {
        CarveOptions o;
        o.pdlThicknessMm = j.at("pdl_thickness_mm").get<double>();
        o.pdlRatio = j.at("pdl_ratio").get<double>();
        o.clearanceVoxels = j.at("clearance_voxels").get<double>();
        o.gapBridgeMm = j.at("gap_bridge_mm").get<double>();
        o.boneShiftMaxMm = j.at("bone_shift_max_mm").get<double>();
        o.gapFacingDeg = j.at("gap_facing_deg").get<double>();
        o.minCapRiseMm = j.at("min_cap_rise_mm").get<double>();
        o.apexTaperMm = j.at("apex_taper_mm").get<double>();
        o.capExclusionMm = j.at("cap_exclusion_mm").get<double>();
        o.pdlKept = j.at("pdl").get<std::string>() == "kept";
        if (j.contains("pdl_profile_mm")) o.profile = profileOf(j.at("pdl_profile_mm"));
        if (j.contains("tooth_pdl_mm"))
            for (const auto& [unn, p] : j.at("tooth_pdl_mm").items()) o.toothPdl[std::stoi(unn)] = profileOf(p);
        if (j.contains("implants")) o.implants = j.at("implants").get<std::set<int>>();
        return o;
    } catch (const std::exception& e) {
        throw Error(name, std::string("carve options: ") + e.what());
    }
}

nlohmann::json toJson(const CarveSummary& s) {
    nlohmann::json teeth = nlohmann::json::array();
    for (const auto& t : s.teeth) {
        teeth.push_back({{"unn", t.unn},
                         {"tooth_volume_mm3", t.toothVolumeMm3},
                         {"pdl_volume_mm3", t.pdlVolumeMm3},
                         {"root_area_fraction", t.rootAreaFraction},
                         {"impacted", t.impacted},
                         {"implant", t.implant},
                         {"thickness_mm",
                          {{"samples", t.thickness.samples},
                           {"min", t.thickness.min},
                           {"p05", t.thickness.p05},
                           {"mean", t.thickness.mean},
                           {"p95", t.thickness.p95},
                           {"max", t.thickness.max}}}});
    }
    return {{"voxel_mm", s.voxelSizeMm},
            {"teeth", teeth},
            {"clearance_voxels_removed", s.clearanceVoxelsRemoved},
            {"tooth_bone_contacts", s.toothBoneContacts},
            {"warnings", s.warnings},
            {"carve_seconds", s.seconds}};
}

void requireBoneContact(const CarveSummary& summary, const JawCase& jawCase, const CarveOptions& options) {
    for (const ToothCarveSummary& t : summary.teeth)
        if (t.pdlVolumeMm3 <= 0 && !t.implant) {
            std::ostringstream reason;
            reason << "tooth " << t.unn << " does not reach the bone (no root surface within the "
                   << options.gapBridgeMm << " mm gap bridge of a socket), so it gets no PDL; is the file in the "
                   << "bone's coordinate frame and of this jaw?";
            throw Error(toothSource(jawCase, t.unn), reason.str());
        }
}

}  // namespace jawmesh
