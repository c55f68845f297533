// Implements levelset/LineWinding.h; what it computes, its rules and its contract are documented there.
#include "levelset/LineWinding.h"

#include "io/Error.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>

namespace jawmesh {

namespace {
struct Hit {
    float t;
    std::uint32_t prim;
};

// Embree hands the filter our context; the hit list rides behind the standard part.
struct CollectContext {
    RTCIntersectContext base;
    std::vector<Hit>* hits;
    const std::int32_t* patch;
    std::int32_t ignorePatch;
};

void collectAllHits(const RTCFilterFunctionNArguments* args) {
    auto* ctx = reinterpret_cast<CollectContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const std::uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
        if (ctx->ignorePatch < 0 || ctx->patch[prim] != ctx->ignorePatch)
            ctx->hits->push_back({RTCRayN_tfar(args->ray, args->N, i), prim});
        args->valid[i] = 0;  // reject, so traversal continues to every other hit
    }
}
}  // namespace

struct LineWindingQuery::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    Vec3 centre = Vec3::Zero();
    double extent = 1.0;  // half diagonal of the bbox, mm
    std::vector<Vec3> vertices;
    std::vector<Tri> triangles;
    std::vector<std::int32_t> patch;
    std::vector<std::int8_t> sign;
};

LineWindingQuery::LineWindingQuery(const std::vector<Vec3>& vertices, const std::vector<Tri>& triangles,
                                   const std::vector<std::int32_t>& patch)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.vertices = vertices;
    m.triangles = triangles;
    m.patch = patch.empty() ? std::vector<std::int32_t>(triangles.size(), 0) : patch;
    m.sign.assign(triangles.size(), 1);
    BBox box;
    for (const Vec3& v : vertices) box.extend(v);
    if (!box.empty()) {
        m.centre = 0.5 * (box.min + box.max);
        m.extent = std::max(0.5 * box.size().norm(), 1e-3);
    }
    m.device = rtcNewDevice("verbose=0");
    if (!m.device) throw Error("Embree: cannot create a device");
    m.scene = rtcNewScene(m.device);
    rtcSetSceneFlags(m.scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), vertices.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(unsigned), triangles.size()));
    if (!vb || !ib) {
        rtcReleaseGeometry(geom);
        throw Error("Embree: cannot allocate geometry buffers (out of memory?)");
    }
    for (std::size_t i = 0; i < vertices.size(); ++i)
        for (int c = 0; c < 3; ++c) vb[3 * i + c] = static_cast<float>(vertices[i][c] - m.centre[c]);
    for (std::size_t i = 0; i < triangles.size(); ++i)
        for (int c = 0; c < 3; ++c) ib[3 * i + c] = static_cast<unsigned>(triangles[i][c]);
    rtcSetGeometryIntersectFilterFunction(geom, collectAllHits);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(m.scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(m.scene);
    if (rtcGetDeviceError(m.device) != RTC_ERROR_NONE) throw Error("Embree: building the BVH failed");
}

LineWindingQuery::~LineWindingQuery() {
    if (impl_->scene) rtcReleaseScene(impl_->scene);
    if (impl_->device) rtcReleaseDevice(impl_->device);
}

void LineWindingQuery::setOrientation(std::vector<std::int8_t> sign) {
    if (sign.size() != impl_->triangles.size()) throw Error("LineWindingQuery: orientation size mismatch");
    impl_->sign = std::move(sign);
}

Vec3 LineWindingQuery::genericDirection(int k) {
    constexpr int kCount = 64;
    const int i = ((k % kCount) + kCount) % kCount;
    // Interleave the hemispheres so the first few directions are far apart.
    const int j = (i % 2 == 0) ? i / 2 : kCount - 1 - i / 2;
    const double z = 1.0 - 2.0 * (j + 0.5) / kCount;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = 2.399963229728653 * j + 0.3183;
    return Vec3(r * std::cos(phi), r * std::sin(phi), z).normalized();
}

std::optional<int> LineWindingQuery::windingAlongLine(const Vec3& p, const Vec3& dirIn, std::int32_t ignorePatch) const {
    const Impl& m = *impl_;
    const Vec3 dir = dirIn.normalized();
    const Vec3 local = p - m.centre;
    const double half = m.extent + local.norm() + 1.0;  // p sits at t = half on the line
    const Vec3 origin = local - half * dir;

    std::vector<Hit> hits;
    CollectContext ctx;
    rtcInitIntersectContext(&ctx.base);
    ctx.hits = &hits;
    ctx.patch = m.patch.data();
    ctx.ignorePatch = ignorePatch;

    RTCRayHit rh;
    rh.ray.org_x = static_cast<float>(origin.x());
    rh.ray.org_y = static_cast<float>(origin.y());
    rh.ray.org_z = static_cast<float>(origin.z());
    rh.ray.dir_x = static_cast<float>(dir.x());
    rh.ray.dir_y = static_cast<float>(dir.y());
    rh.ray.dir_z = static_cast<float>(dir.z());
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = static_cast<float>(2.0 * half);
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.flags = 0;
    rh.ray.time = 0.0f;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m.scene, &ctx.base, &rh);

    // Deterministic order whatever the BVH traversal order was; a primitive counts once.
    std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.prim < b.prim || (a.prim == b.prim && a.t < b.t); });
    hits.erase(std::unique(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.prim == b.prim; }), hits.end());
    std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.t < b.t || (a.t == b.t && a.prim < b.prim); });

    // Hits closer than float resolution at this scale are one crossing of the surface (an edge
    // or vertex hit by several triangles, a duplicate face): keep the net direction, clamped.
    const double mergeTol = 1e-6 * half * 2.0 + 1e-7;
    int total = 0;
    int before = 0;
    std::size_t i = 0;
    while (i < hits.size()) {
        std::size_t j = i;
        int sum = 0;
        while (j < hits.size() && hits[j].t - hits[i].t <= mergeTol) {
            const Tri& tri = m.triangles[hits[j].prim];
            const Vec3& a = m.vertices[static_cast<std::size_t>(tri[0])];
            const Vec3 n = (m.vertices[static_cast<std::size_t>(tri[1])] - a).cross(m.vertices[static_cast<std::size_t>(tri[2])] - a);
            const double d = n.dot(dir) * m.sign[hits[j].prim];
            sum += d < 0 ? 1 : (d > 0 ? -1 : 0);  // entering through the front counts +1
            ++j;
        }
        const int crossing = std::clamp(sum, -1, 1);
        total += crossing;
        if (static_cast<double>(hits[i].t) < half) before += crossing;
        i = j;
    }
    if (total != 0) return std::nullopt;
    return before;
}

}  // namespace jawmesh
