#include "levelset/CarveGaps.h"

#include "io/Error.h"
#include "levelset/CarveMeasure.h"
#include "levelset/Csg.h"

#include <Eigen/Eigenvalues>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace jawmesh {

double pdlThicknessAt(const PdlProfile& p, double s) {
    s = std::clamp(s, 0.0, 1.0);
    return s < 0.5 ? p.cervical + (p.midRoot - p.cervical) * (s / 0.5) : p.midRoot + (p.apical - p.midRoot) * ((s - 0.5) / 0.5);
}

namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::FloatGrid;
using openvdb::Vec3d;
using FloatAcc = FloatGrid::ConstAccessor;

/// Tooth and bone surfaces "face each other" (a gap to bridge) when their outward normals make an
/// angle above 135 degrees.
constexpr double kFacingCos = 0.70710678118654752;

struct Params {
    double voxel = 0.05;
    double ratio = 0.5;
    double uniformThickness = 0.2;
    std::optional<PdlProfile> profile;
    double gapBridge = 0.5;
    double clearance = 0.05;
};

/// Per-tooth working data.
struct ToothWork {
    int unn = 0;
    Label toothL = 0, pdlL = 0;
    FloatGrid::ConstPtr T;   ///< tooth distance, band wide enough for the carving
    FloatGrid::Ptr U;        ///< unsigned distance to the bone surface near the tooth
    CoordBBox box;           ///< index bounds of T's active voxels
    bool profiled = false;
    Vec3d origin{0, 0, 0}, axis{0, 0, 1};
    double hCervical = 0, hApex = 0;
};

double thicknessAt(const ToothWork& t, const Params& P, const Vec3d& world) {
    if (!t.profiled) return P.uniformThickness;
    const double h = (world - t.origin).dot(t.axis);
    const double s = (t.hCervical - h) / std::max(t.hCervical - t.hApex, 1e-6);
    return pdlThicknessAt(*P.profile, s);
}

/// Signed bone distance: sign from the input bone grid (valid everywhere), magnitude from the
/// tooth's unsigned distance to the nearby bone surface (valid where it matters, see carveJaw).
inline double signedBone(FloatAcc& B, FloatAcc& U, const Coord& c) {
    const double u = U.getValue(c);
    return B.getValue(c) < 0 ? -u : u;
}

/// What one tooth's rules say at one voxel (before the clearance between teeth).
struct Local {
    double T = 0;      ///< tooth distance
    double tooth = 0;  ///< carved tooth field
    double pdl = 0;    ///< PDL field
    double fill = 0;   ///< bridged-gap field (negative: gap that becomes socket)
    double excl = 0;   ///< w - T: positive where bone is excluded by this tooth
};

Local evalLocal(const ToothWork& t, const Params& P, FloatAcc& T, FloatAcc& U, FloatAcc& B,
                const openvdb::math::Transform& xf, const Coord& c) {
    Local r;
    r.T = T.getValue(c);
    const double b = signedBone(B, U, c);
    const double th = thicknessAt(t, P, xf.indexToWorld(c));
    const double e = P.ratio * th, w = th - e;
    double gap = r.T + b - P.gapBridge;
    if (gap < 0) {
        const Coord dx(1, 0, 0), dy(0, 1, 0), dz(0, 0, 1);
        const Vec3d gT(T.getValue(c + dx) - T.getValue(c - dx), T.getValue(c + dy) - T.getValue(c - dy),
                       T.getValue(c + dz) - T.getValue(c - dz));
        const Vec3d gB(signedBone(B, U, c + dx) - signedBone(B, U, c - dx), signedBone(B, U, c + dy) - signedBone(B, U, c - dy),
                       signedBone(B, U, c + dz) - signedBone(B, U, c - dz));
        const double lT = gT.length(), lB = gB.length();
        // A clamped field (outside its band) has no direction: treat as not facing.
        const double dot = (lT > 1e-3 * P.voxel && lB > 1e-3 * P.voxel) ? gT.dot(gB) / (lT * lB) : 0.0;
        gap = std::max(gap, (dot + kFacingCos) * P.gapBridge);
    }
    const double socket = std::min(b - e, gap);  // < 0: in the socket of this tooth
    r.tooth = std::max(r.T, std::min(r.T + e, -socket));
    r.pdl = std::max({r.T - w, -(r.T + e), socket});
    r.fill = std::max(-r.T, gap);
    r.excl = w - r.T;
    return r;
}

/// Accessors of one thread to every tooth's grids.
struct Accessors {
    std::vector<FloatAcc> T, U;
    FloatAcc B;
    Accessors(const std::vector<ToothWork>& teeth, const FloatGrid& bone) : B(bone.getConstAccessor()) {
        for (const auto& t : teeth) {
            T.push_back(t.T->getConstAccessor());
            U.push_back(t.U->getConstAccessor());
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

/// Copies the part of `grid` inside index box `box` (leaves and leaf-sized tiles).
FloatGrid::Ptr copyBox(const FloatGrid& grid, const CoordBBox& box) {
    auto out = FloatGrid::create(grid.background());
    out->setTransform(grid.transform().copy());
    out->setGridClass(openvdb::GRID_LEVEL_SET);
    auto acc = grid.getConstAccessor();
    const int dim = int(openvdb::FloatTree::LeafNodeType::DIM);
    const Coord lo = box.min() & ~(dim - 1);
    for (int x = lo.x(); x <= box.max().x(); x += dim)
        for (int y = lo.y(); y <= box.max().y(); y += dim)
            for (int z = lo.z(); z <= box.max().z(); z += dim) {
                const Coord o(x, y, z);
                if (const auto* leaf = grid.tree().probeConstLeaf(o)) {
                    out->tree().addLeaf(new openvdb::FloatTree::LeafNodeType(*leaf));
                } else {
                    const float v = acc.getValue(o);
                    if (v < 0) out->tree().addTile(1, o, v, false);
                }
            }
    return out;
}

/// Unsigned distance (band `bandVoxels`) to the part of the bone surface within `reachMm` of the
/// tooth (T < reachMm). Bone surface = marching-cubes surface of the bone grid around the tooth.
FloatGrid::Ptr boneDistanceNearTooth(const FloatGrid& bone, const FloatGrid& T, const CoordBBox& box, double reachMm,
                                     double bandVoxels) {
    CoordBBox b = box;
    b.expand(4);
    const auto local = copyBox(bone, b);
    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    openvdb::tools::volumeToMesh(*local, points, tris, quads, 0.0, 0.0);
    const auto& xf = T.transform();
    auto acc = T.getConstAccessor();
    std::vector<char> near(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        near[i] = acc.getValue(xf.worldToIndexNodeCentered(Vec3d(points[i]))) < reachMm;
    std::vector<openvdb::Vec3I> keepTris;
    std::vector<openvdb::Vec4I> keepQuads;
    for (const auto& q : quads)
        if (near[q[0]] || near[q[1]] || near[q[2]] || near[q[3]]) keepQuads.push_back(q);
    for (const auto& t : tris)
        if (near[t[0]] || near[t[1]] || near[t[2]]) keepTris.push_back(t);
    if (keepQuads.empty() && keepTris.empty()) {
        auto empty = FloatGrid::create(float(bandVoxels * xf.voxelSize()[0]));
        empty->setTransform(xf.copy());
        return empty;
    }
    return openvdb::tools::meshToUnsignedDistanceField<FloatGrid>(xf, points, keepTris, keepQuads, float(bandVoxels));
}

/// Long axis of the tooth and the cervical / apical heights along it, for the thickness profile.
void fitProfileAxis(ToothWork& t, const Params& P, const FloatGrid& bone, const CarveOptions& options) {
    const auto& xf = t.T->transform();
    std::vector<Vec3d> surface;
    std::vector<char> contact;
    auto T = t.T->getConstAccessor();
    auto U = t.U->getConstAccessor();
    auto B = bone.getConstAccessor();
    const double eCervical = P.ratio * P.profile->cervical;
    for (auto it = t.T->tree().cbeginValueOn(); it; ++it) {
        const double v = *it;
        if (v >= 0 || v < -2 * P.voxel) continue;
        surface.push_back(xf.indexToWorld(it.getCoord()));
        contact.push_back(signedBone(B, U, it.getCoord()) < eCervical + P.voxel);
    }
    if (surface.empty()) return;
    Vec3d mean(0, 0, 0);
    for (const auto& p : surface) mean += p;
    mean /= double(surface.size());
    const auto axes = options.axes.find(t.unn);
    if (axes != options.axes.end()) {
        t.origin = Vec3d(axes->second.crownCentre.x(), axes->second.crownCentre.y(), axes->second.crownCentre.z());
        const auto& a = axes->second.occlusal;
        t.axis = Vec3d(a.x(), a.y(), a.z()).unit();
    } else {
        Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
        for (const auto& p : surface) {
            const Eigen::Vector3d d(p[0] - mean[0], p[1] - mean[1], p[2] - mean[2]);
            cov += d * d.transpose();
        }
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
        const Eigen::Vector3d a = es.eigenvectors().col(2);
        t.origin = mean;
        t.axis = Vec3d(a.x(), a.y(), a.z());
        // Orient towards the crown: the root (bone contact) lies on the negative side.
        double hc = 0;
        std::size_t nc = 0;
        for (std::size_t i = 0; i < surface.size(); ++i)
            if (contact[i]) hc += (surface[i] - t.origin).dot(t.axis), ++nc;
        if (nc && hc / double(nc) > 0) t.axis = -t.axis;
    }
    std::vector<double> hContact;
    t.hApex = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < surface.size(); ++i) {
        const double h = (surface[i] - t.origin).dot(t.axis);
        t.hApex = std::min(t.hApex, h);
        if (contact[i]) hContact.push_back(h);
    }
    if (hContact.empty()) return;
    std::sort(hContact.begin(), hContact.end());
    t.hCervical = hContact[std::size_t(0.95 * double(hContact.size() - 1))];
    t.profiled = t.hCervical > t.hApex;
}

void validate(const CarveOptions& o, const FloatGrid& bone, const std::map<int, FloatGrid::ConstPtr>& teeth) {
    if (!(o.pdlRatio >= 0 && o.pdlRatio <= 1)) throw Error("carve: --pdl-ratio must be in [0, 1]");
    if (!(o.clearanceVoxels >= 0)) throw Error("carve: clearance must be >= 0 voxels");
    if (!(o.gapBridgeMm >= 0)) throw Error("carve: gap bridge must be >= 0 mm");
    const double tMin = o.profile ? std::min({o.profile->cervical, o.profile->midRoot, o.profile->apical}) : o.pdlThicknessMm;
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
        if (!grid) throw Error("carve: tooth " + std::to_string(unn) + " has no grid");
        requireSameTransform(bone, *grid, "carve");
        bandHalfWidthMm(*grid);
    }
}

}  // namespace

LabelField carveJaw(Jaw jaw, const FloatGrid& bone, const std::map<int, FloatGrid::ConstPtr>& teethIn,
                    const CarveOptions& options, CarveSummary& summary, Progress& progress) {
    const auto start = std::chrono::steady_clock::now();
    validate(options, bone, teethIn);
    Params P;
    P.voxel = uniformVoxelSizeMm(bone);
    P.ratio = options.pdlRatio;
    P.uniformThickness = options.profile ? options.profile->midRoot : options.pdlThicknessMm;
    P.profile = options.profile;
    P.gapBridge = options.gapBridgeMm;
    P.clearance = options.clearanceVoxels * P.voxel;
    const double tMax = P.profile ? std::max({P.profile->cervical, P.profile->midRoot, P.profile->apical}) : P.uniformThickness;
    const double eMax = P.ratio * tMax, wMax = tMax - eMax;
    const auto& xf = bone.transform();
    const Label boneL = boneLabel(jaw);
    summary = CarveSummary();
    summary.voxelSizeMm = P.voxel;

    // 1. Per tooth: a band wide enough for the rules, and the distance to the nearby bone.
    const double exVoxels = std::ceil((std::max(P.gapBridge, wMax) + P.clearance) / P.voxel) + 3;
    const double inVoxels = std::ceil(eMax / P.voxel) + 3;
    const double reach = P.gapBridge + 2 * P.voxel;
    const double udfBand = std::ceil((P.gapBridge + eMax) / P.voxel) + 3;
    std::vector<ToothWork> teeth;
    {
        ProgressStage stage(progress, "carve: tooth bands");
        int done = 0;
        for (const auto& [unn, grid] : teethIn) {
            progress.checkCancelled();
            ToothWork t;
            t.unn = unn;
            t.toothL = toothLabel(unn);
            t.pdlL = pdlLabel(unn);
            if (bandHalfWidthMm(*grid) >= std::max(exVoxels, inVoxels) * P.voxel - 1e-6)
                t.T = grid;
            else
                t.T = renormalizeLevelSet(*grid, exVoxels, inVoxels, progress);
            t.box = t.T->evalActiveVoxelBoundingBox();
            t.U = boneDistanceNearTooth(bone, *t.T, t.box, reach, udfBand);
            if (P.profile) fitProfileAxis(t, P, bone, options);
            teeth.push_back(std::move(t));
            stage.update(double(++done) / double(teethIn.size()));
        }
    }

    // 2. Labels and bone distance of every voxel near a tooth, in parallel over leaves.
    openvdb::MaskTree nearMask;
    for (const auto& t : teeth) nearMask.topologyUnion(t.T->tree());
    openvdb::Int32Tree nearLabels(nearMask, kOutsideLabel, kOutsideLabel, openvdb::TopologyCopy());
    openvdb::FloatTree nearBone(nearMask, bone.background(), bone.background(), openvdb::TopologyCopy());
    const float boneBg = bone.background();
    openvdb::tree::LeafManager<openvdb::Int32Tree> nearLeaves(nearLabels);
    {
        ProgressStage stage(progress, "carve: label voxels near teeth");
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nearLeaves.leafCount()), [&](const tbb::blocked_range<std::size_t>& r) {
            if (progress.cancelled()) return;
            Accessors acc(teeth, bone);
            std::vector<Local> loc(teeth.size());
            for (std::size_t li = r.begin(); li != r.end(); ++li) {
                auto& leaf = nearLeaves.leaf(li);
                auto* boneLeaf = nearBone.probeLeaf(leaf.origin());
                CoordBBox lb = leaf.getNodeBoundingBox();
                lb.expand(1);
                const auto cand = candidates(teeth, lb);
                for (auto v = leaf.beginValueOn(); v; ++v) {
                    const Coord c = v.getCoord();
                    double excl = -std::numeric_limits<double>::infinity();
                    double fill = std::numeric_limits<double>::infinity();
                    double mag = std::numeric_limits<double>::infinity();
                    const float bIn = acc.B.getValue(c);
                    if (acc.B.isValueOn(c) && std::abs(bIn) < boneBg) mag = std::abs(bIn);
                    for (int k : cand) {
                        loc[k] = evalLocal(teeth[k], P, acc.T[k], acc.U[k], acc.B, xf, c);
                        excl = std::max(excl, loc[k].excl);
                        fill = std::min(fill, loc[k].fill);
                        mag = std::min(mag, double(acc.U[k].getValue(c)));
                    }
                    const double b = std::max(std::min(bIn < 0 ? -mag : mag, fill), excl);
                    Label label = b < 0 ? boneL : kOutsideLabel;
                    bool owned = false;
                    for (int k : cand) {  // teeth first, then PDLs; UNN order breaks exact ties
                        const double bis = bisector(k, cand, acc, c, P.clearance);
                        if (std::max(loc[k].tooth, bis) < 0) { label = teeth[k].toothL; owned = true; break; }
                    }
                    if (!owned)
                        for (int k : cand) {
                            const double bis = bisector(k, cand, acc, c, P.clearance);
                            if (std::max(loc[k].pdl, bis) < 0) { label = teeth[k].pdlL; break; }
                        }
                    v.setValue(label);
                    boneLeaf->setValueOnly(c, float(std::clamp(b, -double(boneBg), double(boneBg))));
                }
            }
        });
        progress.checkCancelled();
    }

    // 3. Assemble the label grid: bone interior, tooth interiors, then the voxels near teeth.
    LabelField field;
    field.voxelSizeMm = P.voxel;
    field.jaw = jaw;
    auto boneOut = bone.deepCopy();
    boneOut->setName(labelName(boneL));
    {
        ProgressStage stage(progress, "carve: assemble labels");
        const auto boneInside = openvdb::tools::sdfInteriorMask(bone);
        field.labels = openvdb::Int32Grid::create(kOutsideLabel);
        field.labels->setTree(std::make_shared<openvdb::Int32Tree>(boneInside->tree(), kOutsideLabel, boneL, openvdb::TopologyCopy()));
        field.labels->setTransform(xf.copy());
        field.labels->setName("labels");
        auto& lt = field.labels->tree();
        auto& bt = boneOut->tree();
        for (const auto& t : teeth) {
            progress.checkCancelled();
            const auto inside = openvdb::tools::sdfInteriorMask(*t.T);
            for (auto it = inside->tree().cbeginValueOn(); it; ++it) {
                if (it.isTileValue()) {
                    lt.fill(it.getBoundingBox(), t.toothL, true);
                    bt.fill(it.getBoundingBox(), boneBg, false);
                } else if (!nearMask.isValueOn(it.getCoord())) {
                    lt.setValueOn(it.getCoord(), t.toothL);
                    bt.setValueOff(it.getCoord(), boneBg);
                }
            }
        }
        for (auto it = nearLabels.cbeginLeaf(); it; ++it) {
            auto* L = lt.touchLeaf(it->origin());
            auto* BL = bt.touchLeaf(it->origin());
            const auto* nb = nearBone.probeConstLeaf(it->origin());
            for (auto v = it->cbeginValueOn(); v; ++v) {
                const auto off = v.pos();
                if (*v == kOutsideLabel) L->setValueOff(off, kOutsideLabel);
                else L->setValueOn(off, *v);
                BL->setValueOn(off, nb->getValue(off));
            }
        }
    }

    // 4. Clearance, discretely: no voxel of one tooth or its PDL 26-touches another tooth's.
    std::map<Label, int> ownerOf;
    for (int k = 0; k < int(teeth.size()); ++k) ownerOf[teeth[k].toothL] = k, ownerOf[teeth[k].pdlL] = k;
    std::vector<std::vector<Coord>> drops(nearLeaves.leafCount());
    std::vector<std::size_t> boneContacts(nearLeaves.leafCount(), 0);
    {
        ProgressStage stage(progress, "carve: clearance");
        const auto& labels = *field.labels;
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nearLeaves.leafCount()), [&](const tbb::blocked_range<std::size_t>& r) {
            Accessors acc(teeth, bone);
            auto la = labels.getConstAccessor();
            for (std::size_t li = r.begin(); li != r.end(); ++li) {
                for (auto v = nearLeaves.leaf(li).cbeginValueOn(); v; ++v) {
                    const Coord p = v.getCoord();
                    const Label l = la.getValue(p);
                    const auto own = ownerOf.find(l);
                    if (own == ownerOf.end()) continue;
                    const int a = own->second;
                    bool drop = false, touchesBone = false;
                    for (int dx = -1; dx <= 1 && !drop; ++dx)
                        for (int dy = -1; dy <= 1 && !drop; ++dy)
                            for (int dz = -1; dz <= 1 && !drop; ++dz) {
                                const Coord q = p.offsetBy(dx, dy, dz);
                                const Label m = la.getValue(q);
                                if (m == boneL && l == teeth[a].toothL) touchesBone = true;
                                const auto other = ownerOf.find(m);
                                if (other == ownerOf.end() || other->second == a) continue;
                                const int b = other->second;
                                const double marginP = acc.T[b].getValue(p) - acc.T[a].getValue(p);
                                const double marginQ = acc.T[a].getValue(q) - acc.T[b].getValue(q);
                                drop = marginP < marginQ || (marginP == marginQ && teeth[a].unn > teeth[b].unn);
                            }
                    if (drop) drops[li].push_back(p);
                    else if (touchesBone) ++boneContacts[li];
                }
            }
        });
        auto& lt = field.labels->tree();
        for (const auto& d : drops)
            for (const auto& p : d) lt.setValueOff(p, kOutsideLabel), ++summary.clearanceVoxelsRemoved;
        for (auto n : boneContacts) summary.toothBoneContacts += n;
    }

    // 5. Distance grids of teeth and PDLs on each tooth's band, consistent with the labels.
    {
        ProgressStage stage(progress, "carve: region distances");
        for (int k = 0; k < int(teeth.size()); ++k) {
            progress.checkCancelled();
            const auto& t = teeth[k];
            auto toothGrid = t.T->deepCopy();
            auto pdlGrid = FloatGrid::create(t.T->background());
            pdlGrid->setTree(std::make_shared<openvdb::FloatTree>(t.T->tree(), t.T->background(), t.T->background(), openvdb::TopologyCopy()));
            pdlGrid->setTransform(xf.copy());
            openvdb::tree::LeafManager<openvdb::FloatTree> tl(toothGrid->tree());
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tl.leafCount()), [&](const tbb::blocked_range<std::size_t>& r) {
                Accessors acc(teeth, bone);
                auto la = field.labels->getConstAccessor();
                for (std::size_t li = r.begin(); li != r.end(); ++li) {
                    auto& leaf = tl.leaf(li);
                    auto* pl = pdlGrid->tree().probeLeaf(leaf.origin());
                    CoordBBox lb = leaf.getNodeBoundingBox();
                    lb.expand(1);
                    const auto cand = candidates(teeth, lb);
                    for (auto v = leaf.beginValueOn(); v; ++v) {
                        const Coord c = v.getCoord();
                        const Local l = evalLocal(t, P, acc.T[k], acc.U[k], acc.B, xf, c);
                        const double bis = bisector(k, cand, acc, c, P.clearance);
                        double tooth = std::max(l.tooth, bis), pdl = std::max(l.pdl, bis);
                        // Voxels dropped by the clearance pass, or won by another tooth on a tie.
                        const Label lab = la.getValue(c);
                        if (tooth < 0 && lab != t.toothL) tooth = 0.5 * P.voxel;
                        if (pdl < 0 && lab != t.pdlL) pdl = 0.5 * P.voxel;
                        const double bg = t.T->background();
                        v.setValue(float(std::clamp(tooth, -bg, bg)));
                        pl->setValueOnly(c, float(std::clamp(pdl, -bg, bg)));
                    }
                }
            });
            // Deep interior tiles of this tooth that another tooth won (overlapping inputs).
            {
                auto ta = toothGrid->getAccessor();
                auto la = field.labels->getConstAccessor();
                for (auto leaf = nearLabels.cbeginLeaf(); leaf; ++leaf) {
                    if (!t.box.hasOverlap(leaf->getNodeBoundingBox())) continue;
                    for (auto v = leaf->cbeginValueOn(); v; ++v) {
                        const Coord c = v.getCoord();
                        if (!ta.isValueOn(c) && ta.getValue(c) < 0 && la.getValue(c) != t.toothL)
                            ta.setValueOff(c, float(0.5 * P.voxel));
                    }
                }
            }
            toothGrid->setName(labelName(t.toothL));
            toothGrid->setGridClass(openvdb::GRID_LEVEL_SET);
            pdlGrid->setName(labelName(t.pdlL));
            pdlGrid->setGridClass(openvdb::GRID_LEVEL_SET);
            field.distances[t.toothL] = toothGrid;
            field.distances[t.pdlL] = pdlGrid;
        }
        field.distances[boneL] = boneOut;
    }

    // 6. Measurements and warnings.
    {
        ProgressStage stage(progress, "carve: measure");
        for (const auto& t : teeth) {
            progress.checkCancelled();
            ToothCarveSummary s;
            s.unn = t.unn;
            measureTooth(field, t.unn, options.capExclusionMm, s);
            if (s.pdlVolumeMm3 <= 0)
                summary.warnings.push_back("tooth " + std::to_string(t.unn) + " has no bone contact: no PDL");
            else if (s.impacted)
                summary.warnings.push_back("tooth " + std::to_string(t.unn) + " is fully inside bone: closed PDL envelope");
            if (P.profile && !t.profiled)
                summary.warnings.push_back("tooth " + std::to_string(t.unn) + ": no root found for the thickness profile; uniform mid-root value used");
            summary.teeth.push_back(s);
        }
        if (summary.toothBoneContacts)
            summary.warnings.push_back(std::to_string(summary.toothBoneContacts) + " tooth voxels touch bone directly (PDL widening under 2 voxels?)");
    }
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return field;
}

}  // namespace jawmesh
