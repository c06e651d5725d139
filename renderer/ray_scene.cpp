#include "renderer/ray_scene.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace nenrin {

namespace {

[[noreturn]] [[gnu::cold]] void rayOutOfRange(const Ray& ray) {
    throw std::domain_error(fmt::format(
        "renderer: a ray from ({:g}, {:g}, {:g}) along ({:g}, {:g}, {:g}) is outside what "
        "Embree can trace (a camera, light or object placed absurdly far?)",
        ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x, ray.direction.y,
        ray.direction.z));
}

/// Embree asserts (and aborts the process) on a ray it deems invalid: a coordinate beyond
/// ~1.8e18 or not finite, or a negative or NaN extent. Scene inputs are bounded where they are
/// read; this keeps a missed case an error instead of an abort. Every ray is checked, so the
/// tests are combined with & (no branch each; a NaN fails every comparison).
inline void checkRay(const Ray& ray, double tMax) {
    constexpr double kLimit = 1e18;
    const bool ok = (tMax >= 0) & (std::abs(ray.origin.x) < kLimit) &
                    (std::abs(ray.origin.y) < kLimit) & (std::abs(ray.origin.z) < kLimit) &
                    (std::abs(ray.direction.x) < kLimit) & (std::abs(ray.direction.y) < kLimit) &
                    (std::abs(ray.direction.z) < kLimit);
    if (!ok) [[unlikely]]
        rayOutOfRange(ray);
}

/// What a geometry id stands for, and what shading needs of it.
struct GeometryRecord {
    bool isLight = false;
    uint32_t index = 0;
    std::vector<Vec3> normals;  ///< world-space vertex normals (meshes that have them)
    std::vector<std::array<double, 2>> uvs;
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<std::array<Vec3, 2>> uvDerivatives;  ///< per triangle: dP/du, dP/dv
};

/// dP/du and dP/dv of a triangle (zero if its uvs have no area).
std::array<Vec3, 2> uvDerivatives(const Vec3& p0, const Vec3& p1, const Vec3& p2,
                                  const std::array<double, 2>& a, const std::array<double, 2>& b,
                                  const std::array<double, 2>& c) {
    double du1 = b[0] - a[0], dv1 = b[1] - a[1], du2 = c[0] - a[0], dv2 = c[1] - a[1];
    double det = du1 * dv2 - du2 * dv1;
    if (std::abs(det) < 1e-30) return {Vec3{}, Vec3{}};
    Vec3 e1 = p1 - p0, e2 = p2 - p0;
    return {(e1 * dv2 - e2 * dv1) / det, (e2 * du1 - e1 * du2) / det};
}

/// The 12 triangles of a box [-s/2, s/2], wound so normals face outwards.
void boxTriangles(const Vec3& size, std::vector<Vec3>& positions,
                  std::vector<std::array<uint32_t, 3>>& triangles) {
    Vec3 h = size * 0.5;
    for (int i = 0; i < 8; ++i)
        positions.push_back({i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z});
    // Faces as (a, b, c, d) counter-clockwise seen from outside.
    const uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& f : faces) {
        triangles.push_back({f[0], f[1], f[2]});
        triangles.push_back({f[0], f[2], f[3]});
    }
}

/// What Embree found for one ray: the ray (as Embree took it, in floats) and its hit.
struct EmbreeHit {
    float org[3], dir[3], tfar;
    float ng[3], u, v;
    unsigned primID, geomID;
};

/// A SurfaceHit's defaults, field by field: `s = SurfaceHit{}` was a rep stos per ray, whose
/// start-up costs more than these stores.
void resetHit(SurfaceHit& s) {
    static_assert(sizeof(SurfaceHit) == 160, "a new SurfaceHit field: reset it here");
    s.hit = s.isLight = false;
    s.distance = s.u = s.v = 0;
    s.position = s.geometricNormal = s.shadingNormal = s.dpdu = s.dpdv = Vec3{};
    s.index = 0;
}

/// Fills `s` (reset first) with the hit `h`.
void toHit(const EmbreeHit& h, const std::vector<GeometryRecord>& records, SurfaceHit& s) {
    resetHit(s);
    if (h.geomID == RTC_INVALID_GEOMETRY_ID) return;
    s.hit = true;
    s.distance = h.tfar;
    s.position = Vec3{h.org[0], h.org[1], h.org[2]} + Vec3{h.dir[0], h.dir[1], h.dir[2]} * h.tfar;
    s.geometricNormal = normalize(Vec3{h.ng[0], h.ng[1], h.ng[2]});
    s.shadingNormal = s.geometricNormal;
    const GeometryRecord& g = records[h.geomID];
    s.isLight = g.isLight;
    s.index = g.index;
    const auto& t = g.triangles.empty() ? std::array<uint32_t, 3>{} : g.triangles[h.primID];
    double w = 1 - h.u - h.v;
    if (!g.normals.empty()) {
        Vec3 n = g.normals[t[0]] * w + g.normals[t[1]] * h.u + g.normals[t[2]] * h.v;
        if (lengthSquared(n) > 0) s.shadingNormal = normalize(n);
    }
    if (!g.uvs.empty()) {
        s.u = g.uvs[t[0]][0] * w + g.uvs[t[1]][0] * h.u + g.uvs[t[2]][0] * h.v;
        s.v = g.uvs[t[0]][1] * w + g.uvs[t[1]][1] * h.u + g.uvs[t[2]][1] * h.v;
        s.dpdu = g.uvDerivatives[h.primID][0];
        s.dpdv = g.uvDerivatives[h.primID][1];
    }
}

}  // namespace

struct RayScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<GeometryRecord> records;

    void addTriangles(const std::vector<Vec3>& positions,
                      const std::vector<std::array<uint32_t, 3>>& tris, GeometryRecord record) {
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                              positions.size()));
        for (size_t i = 0; i < positions.size(); ++i) {
            v[3 * i] = static_cast<float>(positions[i].x);
            v[3 * i + 1] = static_cast<float>(positions[i].y);
            v[3 * i + 2] = static_cast<float>(positions[i].z);
        }
        auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
        for (size_t i = 0; i < tris.size(); ++i)
            for (int k = 0; k < 3; ++k) idx[3 * i + k] = tris[i][k];
        rtcCommitGeometry(geom);
        unsigned id = rtcAttachGeometry(scene, geom);
        rtcReleaseGeometry(geom);
        if (id != records.size()) throw std::logic_error("embree geometry ids out of order");
        record.triangles = tris;
        if (!record.uvs.empty())
            for (const auto& t : tris)
                record.uvDerivatives.push_back(uvDerivatives(positions[t[0]], positions[t[1]],
                                                             positions[t[2]], record.uvs[t[0]],
                                                             record.uvs[t[1]], record.uvs[t[2]]));
        records.push_back(std::move(record));
    }
};

RayScene::RayScene(const Scene& scene) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.device = rtcNewDevice(nullptr);
    if (!m.device) throw std::runtime_error("embree: could not create a device");
    m.scene = rtcNewScene(m.device);
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& o = scene.objects[i];
        std::vector<Vec3> positions;
        std::vector<std::array<uint32_t, 3>> tris;
        GeometryRecord record;
        record.index = static_cast<uint32_t>(i);
        if (o.shape == ShapeType::Box) {
            boxTriangles(o.size, positions, tris);
        } else {
            positions = o.mesh->positions;
            tris = o.mesh->triangles;
            for (const Vec3& n : o.mesh->normals)
                record.normals.push_back(normalize(o.worldFromObject.vector(n)));
            record.uvs = o.mesh->uvs;
        }
        for (Vec3& p : positions) p = o.worldFromObject.point(p);
        m.addTriangles(positions, tris, std::move(record));
    }
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (l.type != LightType::Rect) continue;
        GeometryRecord record;
        record.isLight = true;
        record.index = static_cast<uint32_t>(i);
        std::vector<Vec3> positions{l.corner, l.corner + l.edgeU, l.corner + l.edgeU + l.edgeV,
                                    l.corner + l.edgeV};
        m.addTriangles(positions, {{0, 1, 2}, {0, 2, 3}}, std::move(record));
    }
    rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(m.scene);
}

RayScene::~RayScene() {
    if (impl_->scene) rtcReleaseScene(impl_->scene);
    if (impl_->device) rtcReleaseDevice(impl_->device);
}

SurfaceHit RayScene::intersect(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = float(ray.origin.x);
    rh.ray.org_y = float(ray.origin.y);
    rh.ray.org_z = float(ray.origin.z);
    rh.ray.dir_x = float(ray.direction.x);
    rh.ray.dir_y = float(ray.direction.y);
    rh.ray.dir_z = float(ray.direction.z);
    rh.ray.tnear = 0;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    checkRay(ray, 0);
    rtcIntersect1(impl_->scene, &context, &rh);
    const EmbreeHit h{{rh.ray.org_x, rh.ray.org_y, rh.ray.org_z},
                      {rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z},
                      rh.ray.tfar,
                      {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z},
                      rh.hit.u,
                      rh.hit.v,
                      rh.hit.primID,
                      rh.hit.geomID};
    SurfaceHit s;
    toHit(h, impl_->records, s);
    return s;
}

void RayScene::intersect16(Strided<const Ray> rays, int count, Strided<SurfaceHit> hits) const {
    alignas(64) int valid[16];
    alignas(64) RTCRayHit16 rh;
    for (int i = 0; i < 16; ++i) {
        valid[i] = i < count ? -1 : 0;
        const Ray& r = rays[i < count ? i : 0];
        if (i < count) checkRay(r, 0);
        rh.ray.org_x[i] = float(r.origin.x);
        rh.ray.org_y[i] = float(r.origin.y);
        rh.ray.org_z[i] = float(r.origin.z);
        rh.ray.dir_x[i] = float(r.direction.x);
        rh.ray.dir_y[i] = float(r.direction.y);
        rh.ray.dir_z[i] = float(r.direction.z);
        rh.ray.tnear[i] = 0;
        rh.ray.tfar[i] = std::numeric_limits<float>::infinity();
        rh.ray.mask[i] = ~0u;
        rh.ray.time[i] = 0;
        rh.ray.flags[i] = 0;
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect16(valid, impl_->scene, &context, &rh);
    for (int i = 0; i < count; ++i) {
        const EmbreeHit h{{rh.ray.org_x[i], rh.ray.org_y[i], rh.ray.org_z[i]},
                          {rh.ray.dir_x[i], rh.ray.dir_y[i], rh.ray.dir_z[i]},
                          rh.ray.tfar[i],
                          {rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]},
                          rh.hit.u[i],
                          rh.hit.v[i],
                          rh.hit.primID[i],
                          rh.hit.geomID[i]};
        toHit(h, impl_->records, hits[i]);
    }
}

void RayScene::occluded16(Strided<const Ray> rays, Strided<const double> tMax, int count,
                          Strided<bool> occluded) const {
    alignas(64) int valid[16];
    alignas(64) RTCRay16 r;
    for (int i = 0; i < 16; ++i) {
        valid[i] = i < count ? -1 : 0;
        const Ray& ray = rays[i < count ? i : 0];
        if (i < count) checkRay(ray, tMax[i]);
        r.org_x[i] = float(ray.origin.x);
        r.org_y[i] = float(ray.origin.y);
        r.org_z[i] = float(ray.origin.z);
        r.dir_x[i] = float(ray.direction.x);
        r.dir_y[i] = float(ray.direction.y);
        r.dir_z[i] = float(ray.direction.z);
        r.tnear[i] = 0;
        r.tfar[i] = float(tMax[i < count ? i : 0]);
        r.mask[i] = ~0u;
        r.time[i] = 0;
        r.flags[i] = 0;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcOccluded16(valid, impl_->scene, &context, &r);
    for (int i = 0; i < count; ++i) occluded[i] = r.tfar[i] < 0;
}

bool RayScene::occluded(const Ray& ray, double tMax) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r{};
    r.org_x = float(ray.origin.x);
    r.org_y = float(ray.origin.y);
    r.org_z = float(ray.origin.z);
    r.dir_x = float(ray.direction.x);
    r.dir_y = float(ray.direction.y);
    r.dir_z = float(ray.direction.z);
    r.tnear = 0;
    r.tfar = float(tMax);
    r.mask = ~0u;
    checkRay(ray, tMax);
    rtcOccluded1(impl_->scene, &context, &r);
    return r.tfar < 0;
}

}  // namespace nenrin
