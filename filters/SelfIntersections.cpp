// Implements filters/SelfIntersections.h; what it computes, its rules and its contract are documented there.
#include "filters/SelfIntersections.h"

#include "io/Error.h"

#include <embree3/rtcore.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace jawmesh {
namespace {

// ---- exact expansion arithmetic (Shewchuk 1997), used only when the float filter is unsure ----
// Fixed capacity on the stack: the orient3d determinant of doubles needs at most 196 components.
struct Expansion {
    int n = 0;
    double v[256];
    Expansion() = default;
    explicit Expansion(double x) : n(1) { v[0] = x; }
};

inline void twoSum(double a, double b, double& x, double& y) {
    x = a + b;
    const double bv = x - a;
    const double av = x - bv;
    y = (a - av) + (b - bv);
}
inline void fastTwoSum(double a, double b, double& x, double& y) {
    x = a + b;
    y = b - (x - a);
}
inline void twoProduct(double a, double b, double& x, double& y) {
    x = a * b;
    y = std::fma(a, b, -x);
}

// e += b, in place (each output slot is written after its input was read), zeros eliminated.
void grow(Expansion& e, double b) {
    double q = b;
    int h = 0;
    for (int i = 0; i < e.n; ++i) {
        double s, err;
        twoSum(q, e.v[i], s, err);
        if (err != 0.0) e.v[h++] = err;
        q = s;
    }
    if (q != 0.0 || h == 0) e.v[h++] = q;
    e.n = h;
}

Expansion add(Expansion e, const Expansion& f) {
    for (int i = 0; i < f.n; ++i) grow(e, f.v[i]);
    return e;
}

Expansion scale(const Expansion& e, double b) {
    Expansion h;
    double q, err;
    twoProduct(e.v[0], b, q, err);
    if (err != 0.0) h.v[h.n++] = err;
    for (int i = 1; i < e.n; ++i) {
        double p1, p0, sum;
        twoProduct(e.v[i], b, p1, p0);
        twoSum(q, p0, sum, err);
        if (err != 0.0) h.v[h.n++] = err;
        fastTwoSum(p1, sum, q, err);
        if (err != 0.0) h.v[h.n++] = err;
    }
    if (q != 0.0 || h.n == 0) h.v[h.n++] = q;
    return h;
}

Expansion mul(const Expansion& e, const Expansion& f) {
    Expansion r(0.0);
    for (int i = 0; i < f.n; ++i) {
        const Expansion s = scale(e, f.v[i]);
        for (int k = 0; k < s.n; ++k) grow(r, s.v[k]);
    }
    return r;
}

Expansion diff(double a, double b) {
    double x, y;
    twoSum(a, -b, x, y);
    Expansion e;
    if (y != 0.0) e.v[e.n++] = y;
    e.v[e.n++] = x;
    return e;
}

Expansion negate(Expansion e) {
    for (int i = 0; i < e.n; ++i) e.v[i] = -e.v[i];
    return e;
}

int sign(const Expansion& e) {
    for (int i = e.n - 1; i >= 0; --i)
        if (e.v[i] != 0.0) return e.v[i] > 0.0 ? 1 : -1;
    return 0;
}

int orient2dExact(double ax, double ay, double bx, double by, double cx, double cy) {
    const double det = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx);
    const double perm = std::abs((ax - cx) * (by - cy)) + std::abs((ay - cy) * (bx - cx));
    if (std::abs(det) > 1e-15 * perm) return det > 0.0 ? 1 : -1;
    if ((ax == cx && ay == cy) || (bx == cx && by == cy)) return 0;
    const Expansion l = mul(diff(ax, cx), diff(by, cy));
    const Expansion r = mul(diff(ay, cy), diff(bx, cx));
    return sign(add(l, negate(r)));
}

// 2D view of 3D points: drop coordinate `axis`.
struct Plane2 {
    int u, v;
    explicit Plane2(int axis) : u((axis + 1) % 3), v((axis + 2) % 3) {}
    int orient(const Vec3& a, const Vec3& b, const Vec3& c) const {
        return orient2dExact(a[u], a[v], b[u], b[v], c[u], c[v]);
    }
};

bool segSeg2(const Plane2& P, const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s) {
    const int o1 = P.orient(p, q, r), o2 = P.orient(p, q, s);
    const int o3 = P.orient(r, s, p), o4 = P.orient(r, s, q);
    if (o1 * o2 > 0 || o3 * o4 > 0) return false;
    if (o1 == 0 && o2 == 0 && o3 == 0 && o4 == 0) {  // collinear: overlap of the projections
        for (int k : {P.u, P.v}) {
            if (std::max(p[k], q[k]) < std::min(r[k], s[k])) return false;
            if (std::max(r[k], s[k]) < std::min(p[k], q[k])) return false;
        }
    }
    return true;
}

bool pointInTri2(const Plane2& P, const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const int s1 = P.orient(a, b, p), s2 = P.orient(b, c, p), s3 = P.orient(c, a, p);
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// A projection in which triangle a, b, c is not degenerate; -1 if none (collinear corners).
int projectionAxis(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 n = (b - a).cross(c - a).cwiseAbs();
    int order[3] = {0, 1, 2};
    std::sort(order, order + 3, [&](int i, int j) { return n[i] > n[j]; });
    for (int axis : order)
        if (Plane2(axis).orient(a, b, c) != 0) return axis;
    return -1;
}

bool segTriCoplanar(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    const int axis = projectionAxis(a, b, c);
    if (axis < 0) {  // degenerate triangle: its edges
        const Plane2 P(projectionAxis(p, q, a) >= 0 ? projectionAxis(p, q, a) : 2);
        return segSeg2(P, p, q, a, b) || segSeg2(P, p, q, b, c) || segSeg2(P, p, q, c, a);
    }
    const Plane2 P(axis);
    return pointInTri2(P, p, a, b, c) || pointInTri2(P, q, a, b, c) || segSeg2(P, p, q, a, b) ||
           segSeg2(P, p, q, b, c) || segSeg2(P, p, q, c, a);
}

// Closed segment p q against closed triangle a b c.
bool segTri(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    const int op = orient3dExact(a, b, c, p), oq = orient3dExact(a, b, c, q);
    if (op * oq > 0) return false;
    if (op == 0 && oq == 0) return segTriCoplanar(p, q, a, b, c);
    const int s1 = orient3dExact(p, q, a, b), s2 = orient3dExact(p, q, b, c),
              s3 = orient3dExact(p, q, c, a);
    return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

/// The triangles Embree sees: primitive i is triangle ids[i] of mesh (all of them without ids).
struct BoxData {
    const SurfaceMesh* mesh;
    const std::vector<std::int32_t>* ids;
    std::int32_t triangle(unsigned prim) const { return ids ? (*ids)[prim] : std::int32_t(prim); }
};

void boundsFunc(const RTCBoundsFunctionArguments* args) {
    const auto& data = *static_cast<const BoxData*>(args->geometryUserPtr);
    const BBox b = triangleBox(*data.mesh, data.mesh->triangles[std::size_t(data.triangle(args->primID))]);
    // Embree boxes are float: widen so that exactly touching triangles are never missed.
    const double pad = 1e-6 * (b.size().maxCoeff() + b.max.cwiseAbs().maxCoeff() + b.min.cwiseAbs().maxCoeff());
    args->bounds_o->lower_x = float(b.min.x() - pad);
    args->bounds_o->lower_y = float(b.min.y() - pad);
    args->bounds_o->lower_z = float(b.min.z() - pad);
    args->bounds_o->upper_x = float(b.max.x() + pad);
    args->bounds_o->upper_y = float(b.max.y() + pad);
    args->bounds_o->upper_z = float(b.max.z() + pad);
}

using PairList = std::vector<std::pair<std::int32_t, std::int32_t>>;

/// What the collision callback needs: the triangles, and per thread the intersecting pairs found.
struct CollideData {
    const BoxData* boxes;
    const std::vector<char>* only;  ///< when set, pairs with neither triangle marked are skipped
    tbb::enumerable_thread_specific<PairList> hits;
};

// Candidates are tested as Embree reports them and only hits are kept: a list of all candidate
// pairs (about a dozen per triangle, mostly neighbours) took 2.2 GB on 5.9 M triangles.
void collideFunc(void* userPtr, RTCCollision* collisions, unsigned int count) {
    auto& data = *static_cast<CollideData*>(userPtr);
    const SurfaceMesh& mesh = *data.boxes->mesh;
    auto& local = data.hits.local();
    for (unsigned int i = 0; i < count; ++i) {
        auto a = data.boxes->triangle(collisions[i].primID0), b = data.boxes->triangle(collisions[i].primID1);
        if (a == b) continue;
        if (a > b) std::swap(a, b);
        if (data.only && !(*data.only)[std::size_t(a)] && !(*data.only)[std::size_t(b)]) continue;
        const Tri& ta = mesh.triangles[std::size_t(a)];
        const Tri& tb = mesh.triangles[std::size_t(b)];
        const Vec3 pa[3] = {mesh.vertices[ta[0]], mesh.vertices[ta[1]], mesh.vertices[ta[2]]};
        const Vec3 pb[3] = {mesh.vertices[tb[0]], mesh.vertices[tb[1]], mesh.vertices[tb[2]]};
        if (trianglesIntersect(pa, ta, pb, tb)) local.emplace_back(a, b);
    }
}

}  // namespace

int orient3dExact(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const double adx = a.x() - d.x(), ady = a.y() - d.y(), adz = a.z() - d.z();
    const double bdx = b.x() - d.x(), bdy = b.y() - d.y(), bdz = b.z() - d.z();
    const double cdx = c.x() - d.x(), cdy = c.y() - d.y(), cdz = c.z() - d.z();
    const double det = adx * (bdy * cdz - bdz * cdy) + bdx * (cdy * adz - cdz * ady) +
                       cdx * (ady * bdz - adz * bdy);
    const double perm = std::abs(adx) * (std::abs(bdy * cdz) + std::abs(bdz * cdy)) +
                        std::abs(bdx) * (std::abs(cdy * adz) + std::abs(cdz * ady)) +
                        std::abs(cdx) * (std::abs(ady * bdz) + std::abs(adz * bdy));
    if (std::abs(det) > 1e-14 * perm) return det > 0.0 ? 1 : -1;
    if ((adx == 0.0 && ady == 0.0 && adz == 0.0) || (bdx == 0.0 && bdy == 0.0 && bdz == 0.0) ||
        (cdx == 0.0 && cdy == 0.0 && cdz == 0.0))
        return 0;  // d coincides with a corner (differences of doubles are 0 only for equal values)
    const Expansion eadx = diff(a.x(), d.x()), eady = diff(a.y(), d.y()), eadz = diff(a.z(), d.z());
    const Expansion ebdx = diff(b.x(), d.x()), ebdy = diff(b.y(), d.y()), ebdz = diff(b.z(), d.z());
    const Expansion ecdx = diff(c.x(), d.x()), ecdy = diff(c.y(), d.y()), ecdz = diff(c.z(), d.z());
    const Expansion m1 = add(mul(ebdy, ecdz), negate(mul(ebdz, ecdy)));
    const Expansion m2 = add(mul(ecdy, eadz), negate(mul(ecdz, eady)));
    const Expansion m3 = add(mul(eady, ebdz), negate(mul(eadz, ebdy)));
    return sign(add(add(mul(eadx, m1), mul(ebdx, m2)), mul(ecdx, m3)));
}

bool triangleDegenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
    return projectionAxis(a, b, c) < 0;
}

bool trianglesIntersect(const Vec3 a[3], const Tri& ia, const Vec3 b[3], const Tri& ib) {
    // A triangle with a repeated index is degenerate (reported separately); the shared-vertex
    // logic below needs three distinct indices on each side.
    const auto repeats = [](const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[0] == t[2]; };
    if (repeats(ia) || repeats(ib)) return false;
    int sharedA[3], sharedB[3], nShared = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (ia[i] == ib[j]) {
                sharedA[nShared] = i;
                sharedB[nShared] = j;
                ++nShared;
            }
    if (nShared >= 3) return true;
    if (nShared == 2) {
        const Vec3& s = a[sharedA[0]];
        const Vec3& t = a[sharedA[1]];
        const Vec3& ao = a[3 - sharedA[0] - sharedA[1]];
        const Vec3& bo = b[3 - sharedB[0] - sharedB[1]];
        if (orient3dExact(s, t, ao, bo) != 0) return false;
        const int axis = projectionAxis(s, t, ao);
        if (axis < 0) return false;  // degenerate, reported separately
        const Plane2 P(axis);
        return P.orient(s, t, ao) * P.orient(s, t, bo) > 0;
    }
    if (nShared == 1) {
        const int i = sharedA[0], j = sharedB[0];
        return segTri(a[(i + 1) % 3], a[(i + 2) % 3], b[0], b[1], b[2]) ||
               segTri(b[(j + 1) % 3], b[(j + 2) % 3], a[0], a[1], a[2]);
    }
    for (int k = 0; k < 3; ++k) {
        if (segTri(a[k], a[(k + 1) % 3], b[0], b[1], b[2])) return true;
        if (segTri(b[k], b[(k + 1) % 3], a[0], a[1], a[2])) return true;
    }
    return false;
}

namespace {

/// The intersecting pairs among the triangles `ids` of `mesh` (all without ids; with `only`: pairs
/// with a flagged one), unsorted: Embree's collision of their boxes, each candidate tested exactly.
PairList collidingPairs(const SurfaceMesh& mesh, const std::vector<std::int32_t>* ids, const std::vector<char>* only) {
    RTCDevice device = rtcNewDevice(nullptr);
    if (!device) throw Error("self-intersection check: cannot create an Embree device");
    std::unique_ptr<RTCDeviceTy, void (*)(RTCDevice)> deviceGuard(device, rtcReleaseDevice);
    RTCScene scene = rtcNewScene(device);
    std::unique_ptr<RTCSceneTy, void (*)(RTCScene)> sceneGuard(scene, rtcReleaseScene);
    BoxData data{&mesh, ids};
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, unsigned(ids ? ids->size() : mesh.triangles.size()));
    rtcSetGeometryUserData(geom, &data);
    rtcSetGeometryBoundsFunction(geom, boundsFunc, nullptr);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);

    CollideData collide{&data, only, {}};
    rtcCollide(scene, scene, collideFunc, &collide);
    PairList pairs;
    for (auto& local : collide.hits) pairs.insert(pairs.end(), local.begin(), local.end());
    return pairs;
}

/// The flagged triangles and every triangle whose box may meet one of theirs (a hash of grid
/// cells as large as the largest flagged box, so each flagged box covers at most 8): a few
/// flagged triangles then need no collision structure over the whole surface. Ascending.
std::vector<std::int32_t> aroundFlagged(const SurfaceMesh& mesh, const std::vector<char>& only) {
    const std::size_t nt = mesh.triangles.size();
    double cellMm = 0;
    for (std::size_t t = 0; t < nt; ++t)
        if (only[t]) cellMm = std::max(cellMm, triangleBox(mesh, mesh.triangles[t]).size().maxCoeff());
    cellMm = std::max(cellMm, 1e-9) * 1.01;
    const auto cellRange = [&](const BBox& b, Eigen::Vector3i& lo, Eigen::Vector3i& hi) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = int(std::floor(b.min[a] / cellMm)) - 1;  // a cell of slack for the float padding
            hi[a] = int(std::floor(b.max[a] / cellMm)) + 1;
        }
    };
    const auto key = [](int x, int y, int z) {
        return (std::uint64_t(std::uint32_t(x) & 0x1fffff) << 42) | (std::uint64_t(std::uint32_t(y) & 0x1fffff) << 21) |
               std::uint64_t(std::uint32_t(z) & 0x1fffff);
    };
    std::vector<std::uint64_t> cells;
    for (std::size_t t = 0; t < nt; ++t) {
        if (!only[t]) continue;
        Eigen::Vector3i lo, hi;
        cellRange(triangleBox(mesh, mesh.triangles[t]), lo, hi);
        for (int x = lo[0]; x <= hi[0]; ++x)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int z = lo[2]; z <= hi[2]; ++z) cells.push_back(key(x, y, z));
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    std::vector<char> keep(nt, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 4096), [&](const auto& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
            if (only[t]) {
                keep[t] = 1;
                continue;
            }
            const BBox b = triangleBox(mesh, mesh.triangles[t]);
            Eigen::Vector3i lo, hi;
            cellRange(b, lo, hi);
            // the box's own cells, shrunk back by the slack (a flagged cell within one is enough);
            // a box across many cells is simply kept
            if ((hi - lo).maxCoeff() > 10) {
                keep[t] = 1;
                continue;
            }
            for (int x = lo[0] + 1; x < hi[0] && !keep[t]; ++x)
                for (int y = lo[1] + 1; y < hi[1] && !keep[t]; ++y)
                    for (int z = lo[2] + 1; z < hi[2] && !keep[t]; ++z)
                        keep[t] = std::binary_search(cells.begin(), cells.end(), key(x, y, z));
        }
    });
    std::vector<std::int32_t> out;
    for (std::size_t t = 0; t < nt; ++t)
        if (keep[t]) out.push_back(std::int32_t(t));
    return out;
}

}  // namespace

SelfIntersectionReport findSelfIntersections(const SurfaceMesh& mesh, const std::vector<char>* only) {
    SelfIntersectionReport report;
    const auto nv = std::int32_t(mesh.vertices.size());
    for (const Tri& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
            if (t[k] < 0 || t[k] >= nv) throw Error("self-intersection check: vertex index out of range");
    const std::size_t nt = mesh.triangles.size();
    if (nt == 0) return report;
    if (only && only->size() != nt) throw Error("self-intersection check: the triangle marks do not match the mesh");
    for (std::size_t i = 0; i < nt; ++i) {
        if (only && !(*only)[i]) continue;
        const Tri& t = mesh.triangles[i];
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
            triangleDegenerate(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]))
            report.degenerate.push_back(std::int32_t(i));
    }
    if (!only) {
        report.pairs = collidingPairs(mesh, nullptr, nullptr);
    } else {
        // Only the flagged triangles and those near them take part.
        const std::vector<std::int32_t> part = aroundFlagged(mesh, *only);
        report.pairs = collidingPairs(mesh, &part, only);
    }
    std::sort(report.pairs.begin(), report.pairs.end());  // the same list whatever the threads
    report.pairs.erase(std::unique(report.pairs.begin(), report.pairs.end()), report.pairs.end());
    return report;
}

}  // namespace jawmesh
