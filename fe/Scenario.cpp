// Implements fe/Scenario.h; what it computes, its rules and its contract are documented there.
#include "fe/Scenario.h"

#include "fe/CloseBite.h"
#include "fe/ExteriorFaces.h"
#include "io/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

namespace jawmesh {
namespace {

const Vec3& at(const std::vector<Vec3>& nodes, std::int32_t i) { return nodes[static_cast<std::size_t>(i)]; }

Vec3 centroid(const std::vector<Vec3>& nodes, const Tri& t) {
    return (at(nodes, t[0]) + at(nodes, t[1]) + at(nodes, t[2])) / 3.0;
}

/// Exterior nodes of `label` whose height along `up` is within `depthMm` of the extreme (the
/// lowest when fromBottom, else the highest), and the faces made only of such nodes.
FixedSet slab(const TetMesh& mesh, const std::vector<ExteriorFace>& exterior, Label label, const Vec3& up,
              double depthMm, bool fromBottom, const std::string& name) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const ExteriorFace& f : exterior)
        if (f.label == label)
            for (std::int32_t v : f.nodes) {
                const double h = up.dot(at(mesh.nodes, v));
                lo = std::min(lo, h), hi = std::max(hi, h);
            }
    auto inSlab = [&](std::int32_t v) {
        const double h = up.dot(at(mesh.nodes, v));
        return fromBottom ? h <= lo + depthMm : h >= hi - depthMm;
    };
    FixedSet set;
    set.name = name;
    std::set<std::int32_t> nodes;
    for (const ExteriorFace& f : exterior) {
        if (f.label != label) continue;
        int inside = 0;
        for (std::int32_t v : f.nodes)
            if (inSlab(v)) nodes.insert(v), ++inside;
        if (inside == 3) set.faces.push_back(f.nodes);
    }
    set.nodes.assign(nodes.begin(), nodes.end());
    return set;
}

std::vector<Label> bonesIn(const TetMesh& mesh) {
    std::set<Label> bones;
    for (Label l : mesh.labels)
        if (labelKind(l) == LabelKind::Bone) bones.insert(l);
    return {bones.begin(), bones.end()};
}

Jaw jawOfBone(Label bone) { return bone == boneLabel(Jaw::Mandible) ? Jaw::Mandible : Jaw::Maxilla; }

std::string fmt(double v) {
    std::ostringstream s;
    s.precision(3);
    s << v;
    return s.str();
}

}  // namespace

FeScenario tippingScenario(const TetMesh& mesh, const std::map<int, ToothAxes>& axes, const TippingOptions& o) {
    FeScenario s;
    s.name = "tipping";
    const std::vector<Label> bones = bonesIn(mesh);
    if (bones.empty()) throw Error("tipping scenario: the mesh has no bone region to fix");
    const std::vector<ExteriorFace> exterior = exteriorFaces(mesh);
    std::map<int, Label> teethInMesh;  // UNN -> its tooth's or implant's label
    for (Label l : mesh.labels)
        if (isToothLike(labelKind(l))) teethInMesh[labelUnn(l)] = l;

    for (Label bone : bones) {
        const Jaw jaw = jawOfBone(bone);
        // "Up" from the teeth's own long axes, so the base is found whatever the scan's frame.
        Vec3 occlusal = Vec3::Zero();
        for (const auto& [unn, a] : axes)
            if (jawOfTooth(unn) == jaw && teethInMesh.count(unn)) occlusal += a.occlusal;
        Vec3 up = occlusal.norm() > 1e-9 ? Vec3(occlusal.normalized()) : Vec3::UnitZ();
        if (jaw == Jaw::Maxilla && occlusal.norm() > 1e-9) up = -up;
        if (occlusal.norm() <= 1e-9) s.notes.push_back(jawName(jaw) + ": no tooth axes, +z taken as superior for the base");
        const bool mandible = jaw == Jaw::Mandible;
        FixedSet base = slab(mesh, exterior, bone, up, mandible ? o.mandibleBaseMm : o.maxillaBaseMm, mandible,
                             "fixed_base_" + jawName(jaw));
        if (base.nodes.empty()) throw Error("tipping scenario: no exterior node on the " + jawName(jaw) + " bone");
        s.fixed.push_back(std::move(base));
    }

    for (const auto& [unn, label] : teethInMesh) {
        const auto it = axes.find(unn);
        if (it == axes.end()) {
            s.notes.push_back("tooth " + std::to_string(unn) + ": no axes, not loaded");
            continue;
        }
        const ToothAxes& a = it->second;
        std::vector<const ExteriorFace*> labialFaces;
        for (const ExteriorFace& f : exterior)
            if (f.label == label && triangleNormal(mesh.nodes, f.nodes).dot(a.labial) > 0) labialFaces.push_back(&f);
        if (labialFaces.empty()) {
            s.notes.push_back("tooth " + std::to_string(unn) + ": no exposed labial crown face, not loaded");
            continue;
        }
        SurfaceLoad load;
        load.name = "load_tooth_" + std::to_string(unn);
        load.unn = unn;
        load.targetMm = a.crownCentre + o.loadOffsetMm * a.labial;
        double best = std::numeric_limits<double>::infinity();
        for (const ExteriorFace* f : labialFaces)
            for (std::int32_t v : f->nodes) {
                const double d = (at(mesh.nodes, v) - load.targetMm).squaredNorm();
                if (d < best) best = d, load.referenceNode = v;
            }
        const Vec3 centre = at(mesh.nodes, load.referenceNode);
        // A patch of several faces, never one triangle: grow the radius on coarse crowns.
        double radius = o.patchRadiusMm;
        for (;;) {
            load.faces.clear();
            for (const ExteriorFace* f : labialFaces)
                if ((centroid(mesh.nodes, f->nodes) - centre).norm() <= radius) load.faces.push_back(f->nodes);
            if (load.faces.size() >= o.minPatchFaces || radius >= 4.0 * o.patchRadiusMm) break;
            radius *= 1.5;
        }
        if (load.faces.size() < 2) {
            s.notes.push_back("tooth " + std::to_string(unn) + ": crown too coarse for a load patch, not loaded");
            continue;
        }
        for (const Tri& t : load.faces) load.areaMm2 += triangleArea(mesh.nodes, t);
        load.totalForceN = -o.forceN * a.labial;
        if (radius > o.patchRadiusMm)
            s.notes.push_back("tooth " + std::to_string(unn) + ": load patch radius grown to " + fmt(radius) + " mm");
        s.loads.push_back(std::move(load));
    }
    if (s.loads.empty()) throw Error("tipping scenario: no tooth could be loaded (missing axes or crowns)");
    return s;
}

FeScenario bitingScenario(const TetMesh& mesh, const BitingOptions& o) {
    FeScenario s;
    s.name = "biting";
    s.contact = true;
    const Label mandible = boneLabel(Jaw::Mandible), maxilla = boneLabel(Jaw::Maxilla);
    Vec3 cMand = Vec3::Zero(), cMax = Vec3::Zero();
    double nMand = 0, nMax = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        if (mesh.labels[t] != mandible && mesh.labels[t] != maxilla) continue;
        Vec3 c = Vec3::Zero();
        for (std::int32_t v : mesh.tets[t]) c += at(mesh.nodes, v) / 4.0;
        if (mesh.labels[t] == mandible) cMand += c, ++nMand;
        else cMax += c, ++nMax;
    }
    if (nMand == 0 || nMax == 0) throw Error("biting scenario needs both jaws (mandible and maxilla bone) in one mesh");
    const Vec3 up = (cMax / nMax - cMand / nMand).normalized();
    const std::vector<ExteriorFace> exterior = exteriorFaces(mesh);
    s.fixed.push_back(slab(mesh, exterior, maxilla, up, o.maxillaTopMm, false, "fixed_top_maxilla"));
    FixedSet base = slab(mesh, exterior, mandible, up, o.mandibleBaseMm, true, "base_mandible");
    int vertical = 0;
    up.cwiseAbs().maxCoeff(&vertical);
    base.fixedDofs = {true, true, true};
    base.fixedDofs[static_cast<std::size_t>(vertical)] = false;
    if (std::abs(up[vertical]) < 0.95)
        s.notes.push_back("the jaws' vertical direction is " + fmt(std::acos(std::abs(up[vertical])) * 180.0 / M_PI) +
                          " degrees off the nearest coordinate axis; the mandible base slides along that axis");
    SurfaceLoad push;
    push.name = "load_mandible_base";
    push.faces = base.faces;
    for (const Tri& t : push.faces) push.areaMm2 += triangleArea(mesh.nodes, t);
    Vec3 dir = Vec3::Zero();
    dir[vertical] = up[vertical] > 0 ? 1.0 : -1.0;  // along the free dof only
    push.totalForceN = o.forceN * dir;
    if (push.faces.empty() || push.areaMm2 <= 0) throw Error("biting scenario: the mandible base has no exterior faces");
    const double gap = biteGapMm(mesh, exterior, dir);
    if (std::isinf(gap))
        s.notes.push_back("the crowns of the two jaws do not face each other along the bite: the jaws are left apart");
    else if (gap > 0) {
        s.mandibleOffsetMm = gap * dir;
        s.notes.push_back("mandible moved " + fmt(gap) + " mm along the bite so that the crowns touch");
    }
    s.fixed.push_back(std::move(base));
    s.loads.push_back(std::move(push));
    return s;
}

}  // namespace jawmesh
