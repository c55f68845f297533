// Implements prepareTooth of levelset/CarveRules.h: each tooth's band and the distances carving
// needs beyond the input bands (gap bridging, overlaps), and the root axis for the PDL profile.
#include "levelset/CarveRules.h"

#include "levelset/Csg.h"
#include "levelset/ToothLongAxis.h"

#include <openvdb/tools/ChangeBackground.h>
#include <openvdb/tools/Morphology.h>

#include <vector>

namespace jawmesh::carve {
namespace {

/// Long axis of the tooth and the cervical / apical heights along it, for the thickness profile
/// and the apex taper of the erosion.
void fitRootAxis(ToothWork& t, const CarveRules& rules, const FloatGrid& bone, const CarveOptions& options) {
    const auto& xf = t.T->transform();
    std::vector<Vec3d> surface;
    std::vector<char> contact;
    auto T = t.T->getConstAccessor();
    auto X = t.X->getConstAccessor();
    auto B = bone.getConstAccessor();
    // Contact: bone within the root's erosion of its surface, or, for a kept PDL (no erosion), within
    // the PDL's thickness (else no tooth of a kept PDL had a root: no cervical height, no apex).
    const double tCervical = t.profile ? t.profile->cervical : t.uniformThickness;
    const double eCervical = rules.pdlKept ? tCervical : rules.ratio * tCervical;
    for (auto it = t.T->tree().cbeginValueOn(); it; ++it) {
        const double v = *it;
        if (v >= 0 || v < -2 * rules.voxel) continue;
        surface.push_back(xf.indexToWorld(it.getCoord()));
        contact.push_back(signedBone(B, X, rules, it.getCoord()) < eCervical + rules.voxel);
    }
    if (surface.empty()) return;
    const auto given = options.axes.find(t.unn);
    const LongAxis axis = toothLongAxis(surface, contact, given != options.axes.end() ? &given->second : nullptr);
    t.origin = axis.origin;
    t.axis = axis.axis;
    std::vector<double> hContact;
    t.hApex = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < surface.size(); ++i) {
        const double h = heightOf(t, surface[i]);
        t.hApex = std::min(t.hApex, h);
        if (contact[i]) hContact.push_back(h);
    }
    if (hContact.empty()) return;
    std::sort(hContact.begin(), hContact.end());
    t.hCervical = hContact[std::size_t(0.95 * double(hContact.size() - 1))];
    t.hasRoot = t.hCervical > t.hApex;
}

}  // namespace

/// The working fields of one tooth. The tooth band is used as given (re-normalised only when the
/// input band is narrower than the PDL rules need: a thicker PDL on it or a neighbour; extending it
/// outside by closest-point propagation instead left a 0.3 mm PDL 0.278 mm thick on the shared
/// mandible, against 0.297 mm). Gap bridging needs T and B beyond their bands,
/// but only where a gap can be: outside both, with T + B < gapBridge, so T < gapBridge and
/// B < gapBridge + e. There (and only there) both are extended by closest-point propagation
/// (extendExteriorDistance): B within reach of the tooth, then T where bone is near.
void prepareTooth(ToothWork& t, const FloatGrid& tooth, const FloatGrid& bone, const CarveRules& rules, double exVoxels,
                  double inVoxels, const CarveOptions& options) {
    FloatGrid::Ptr T;
    if (bandHalfWidthMm(tooth) >= std::max(exVoxels, inVoxels) * rules.voxel - 1e-6)
        T = tooth.deepCopy();
    else
        T = renormalizeLevelSet(tooth, exVoxels + 1, inVoxels + 1);
    const double bgT = bandHalfWidthMm(*T);
    // Chebyshev dilation of the band by `reach` voxels covers every point with T < gapBridge.
    const int reach = std::max(0, int(std::ceil((rules.gapBridge - bgT) / rules.voxel)) + 1);
    openvdb::MaskTree near(T->tree(), false, openvdb::TopologyCopy());
    if (reach > 0)
        openvdb::tools::dilateActiveValues(near, reach, openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::IGNORE_TILES);
    // Bone distances are not needed deeper in the tooth than e (there it is tooth whatever B is).
    const double eMax = rules.ratio * thicknessRangeMm(t.profile, t.uniformThickness).second;
    {
        const float deep = float(-(eMax + rules.voxel));
        auto ta = T->getConstAccessor();
        for (auto leaf = near.beginLeaf(); leaf; ++leaf)
            for (openvdb::Index i = 0; i < openvdb::MaskTree::LeafNodeType::SIZE; ++i)
                if (leaf->isValueOn(i) && ta.getValue(leaf->offsetToGlobalCoord(i)) < deep) leaf->setValueOff(i);
    }
    t.X = extendExteriorDistance(bone, near, rules.far);
    t.T = T;
    fitRootAxis(t, rules, bone, options);
    openvdb::MaskTree nearBone(t.X->tree(), false, openvdb::TopologyCopy());
    for (auto leaf = near.cbeginLeaf(); leaf; ++leaf)
        if (const auto* bl = bone.tree().probeConstLeaf(leaf->origin()))
            nearBone.touchLeaf(leaf->origin())->getValueMask() |= bl->getValueMask();
    // Near the apex the socket side widens by what the erosion gives up (erosionShare), past the
    // band: T is needed there whether or not the bone band reaches.
    if (t.hasRoot && rules.apexTaper > 0) {
        const auto& xf = T->transform();
        const double top = t.hApex + rules.apexTaper + rules.voxel;
        for (auto leaf = near.cbeginLeaf(); leaf; ++leaf) {
            openvdb::MaskTree::LeafNodeType* out = nullptr;
            for (auto v = leaf->cbeginValueOn(); v; ++v)
                if (heightOf(t, xf.indexToWorld(v.getCoord())) < top) {
                    if (!out) out = nearBone.touchLeaf(leaf->origin());
                    out->setValueOn(v.pos());
                }
        }
    }
    nearBone.topologyIntersection(near);
    const auto Tx = extendExteriorDistance(*T, nearBone, rules.far);
    openvdb::tools::changeLevelSetBackground(T->tree(), float(rules.far));
    auto ta = T->getAccessor();
    for (auto it = Tx->tree().cbeginValueOn(); it; ++it) ta.setValue(it.getCoord(), *it);
    t.box = T->evalActiveVoxelBoundingBox();
    // Overlaps of root and bone (evalLocal) need B inside the bone down to boneShiftMax, past its
    // band, and its gradient a voxel farther, but only around band voxels where the overlap
    // (T + B, with B clamped: an upper bound) is already deeper than the least one the rule acts
    // on (boneShiftMax - w, w at most t - e / 2 at the apex), two voxels beyond for the gradient.
    const auto [tMin, tMax] = thicknessRangeMm(t.profile, t.uniformThickness);
    const double gTrigger = tMax - kApexErosionShare * rules.ratio * tMin - rules.boneShiftMax;
    openvdb::MaskTree overlap(false);
    {
        auto ba = bone.getConstAccessor();
        auto oa = openvdb::tree::ValueAccessor<openvdb::MaskTree>(overlap);
        for (auto it = tooth.tree().cbeginValueOn(); it; ++it)
            if (*it + ba.getValue(it.getCoord()) < gTrigger) oa.setValueOn(it.getCoord());
    }
    if (overlap.empty()) return;
    openvdb::tools::dilateActiveValues(overlap, 2, openvdb::tools::NN_FACE_EDGE_VERTEX, openvdb::tools::IGNORE_TILES);
    // Deep enough for every point a PDL of thickness t could take (T < t, so B > g - t): with no
    // bone shift (a kept PDL, keptPdlCarveOptions) the floor still moves the bone by up to t.
    const auto inside = extendInteriorDistance(bone, overlap, std::max(rules.boneShiftMax, tMax) + 3 * rules.voxel);
    auto xa = t.X->getAccessor();
    for (auto it = inside->tree().cbeginValueOn(); it; ++it) xa.setValue(it.getCoord(), *it);
}

}  // namespace jawmesh::carve
