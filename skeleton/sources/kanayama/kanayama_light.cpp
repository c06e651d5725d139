// Leaf-sphere light: the O(n^2) reference and the Embree tracer share chordQuanta() and
// finishLight(), so they agree exactly (see kanayama_light.h).
#include "skeleton/sources/kanayama/kanayama_light.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "util/hash.h"

namespace nenrin {

namespace {

constexpr double kChordQuantum = 1e-7;   // m: chords are summed as integers of this
constexpr double kMaxOpticalDepth = 10;  // beyond this a direction counts as dark (e^-10)

/// Length of ray o + t d (t > 0, |d| = 1) inside the sphere, in chord quanta.
int64_t chordQuanta(const Vec3& o, const Vec3& d, const LeafSphere& s) {
    Vec3 oc = s.center - o;
    double b = dot(oc, d);
    double disc = b * b - (lengthSquared(oc) - s.radius * s.radius);
    if (disc <= 0) return 0;
    double h = std::sqrt(disc);
    double t1 = b + h;
    if (t1 <= 0) return 0;
    double chord = t1 - std::max(b - h, 0.0);
    return static_cast<int64_t>(std::llround(chord / kChordQuantum));
}

int64_t quantaCap(double extinction) {
    return static_cast<int64_t>(std::ceil(kMaxOpticalDepth / (extinction * kChordQuantum)));
}

SphereLight finishLight(const std::vector<int64_t>& quanta, const SkyDome& dome,
                        const LeafLightParameters& p) {
    double sum = 0;
    Vec3 dir;
    for (size_t k = 0; k < quanta.size(); ++k) {
        double t = std::exp(-p.extinction * kChordQuantum * static_cast<double>(quanta[k]));
        double w = dome.weights[k] * t;
        sum += w;
        dir += dome.directions[k] * w;
    }
    SphereLight out;
    out.light = p.brightness * sum;
    out.brightestDirection = lengthSquared(dir) > 0 ? normalize(dir) : Vec3{0, 0, 1};
    return out;
}

template <typename Body>
void forEachSphere(size_t n, int threads, const Body& body) {
    auto run = [&] {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 8),
                          [&](const tbb::blocked_range<size_t>& r) {
                              _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
                              _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
                              body(r);
                          });
    };
    if (threads > 0) {
        // At most the cores (TBB warns past them); the light does not depend on the count.
        tbb::task_arena arena(std::min(threads, tbb::info::default_concurrency()));
        arena.execute(run);
    } else {
        run();
    }
}

}  // namespace

SkyDome makeSkyDome(int directionCount) {
    if (directionCount < 1) throw std::invalid_argument("makeSkyDome: need >= 1 direction");
    SkyDome dome;
    // Cells of equal solid angle: rows in z = sin(elevation), columns in azimuth.
    int rows = std::max(1, static_cast<int>(std::lround(std::sqrt(directionCount / 2.0))));
    constexpr uint64_t kDomeSeed = 0x6b616e6179616d61ull;  // fixed: one dome for every tree
    double total = 0;
    for (int k = 0; k < directionCount; ++k) {
        int row = k * rows / directionCount;
        int rowStart = (row * directionCount + rows - 1) / rows;
        int rowEnd = ((row + 1) * directionCount + rows - 1) / rows;
        int column = k - rowStart, columns = rowEnd - rowStart;
        double z = (row + uniform01(kDomeSeed, k, 0)) / rows;
        double phi = 2 * std::numbers::pi * (column + uniform01(kDomeSeed, k, 1)) / columns;
        z = std::clamp(z, 1e-6, 1.0);
        double s = std::sqrt(1 - z * z);
        dome.directions.push_back({s * std::cos(phi), s * std::sin(phi), z});
        // Equal solid angle per row, shared among the row's columns.
        double w = (1 + 2 * z) / 3 / (static_cast<double>(rows) * columns);
        dome.weights.push_back(w);
        total += w;
    }
    for (double& w : dome.weights) w /= total;
    return dome;
}

std::vector<SphereLight> leafLightReference(const std::vector<LeafSphere>& spheres,
                                            const SkyDome& dome, const LeafLightParameters& p) {
    size_t n = spheres.size(), K = dome.directions.size();
    std::vector<SphereLight> out(n);
    if (p.extinction <= 0) {
        std::vector<int64_t> zero(K, 0);
        SphereLight open = finishLight(zero, dome, p);
        std::fill(out.begin(), out.end(), open);
        return out;
    }
    int64_t cap = quantaCap(p.extinction);
    forEachSphere(n, p.threads, [&](const tbb::blocked_range<size_t>& range) {
        std::vector<int64_t> quanta(K);
        for (size_t i = range.begin(); i != range.end(); ++i) {
            std::fill(quanta.begin(), quanta.end(), 0);
            const Vec3& o = spheres[i].center;
            for (size_t j = 0; j < n; ++j) {
                if (j == i) continue;
                // Project sphere j onto the dome: a disc of angular radius asin(r / d).
                Vec3 oc = spheres[j].center - o;
                double d2 = lengthSquared(oc), r = spheres[j].radius;
                double cosDisc = -1;  // the viewer inside sphere j: the whole dome
                Vec3 u{0, 0, 1};
                if (d2 > r * r) {
                    double d = std::sqrt(d2);
                    u = oc / d;
                    double sinDisc = r / d;
                    if (u.z < -sinDisc) continue;  // wholly below the horizon
                    // Conservative margin: the chord test decides, this only prunes.
                    cosDisc = std::sqrt(1 - sinDisc * sinDisc) - 1e-9;
                }
                for (size_t k = 0; k < K; ++k) {
                    if (dot(u, dome.directions[k]) < cosDisc) continue;
                    quanta[k] += chordQuanta(o, dome.directions[k], spheres[j]);
                }
            }
            for (int64_t& q : quanta) q = std::min(q, cap);
            out[i] = finishLight(quanta, dome, p);
        }
    });
    return out;
}

// ---------------------------------------------------------------------------------------------
// Embree tracer

struct LeafLightTracer::Device {
    RTCDevice device = nullptr;
};

namespace {

/// Extends Embree's context (first member) with what the occlusion callback needs.
struct LightRayContext {
    RTCIntersectContext context;
    const LeafSphere* spheres;
    const SkyDome* dome;
    Vec3 origin;
    uint32_t self;
    int64_t cap;
    int64_t* quanta;  // per dome direction
};

void sphereBounds(const RTCBoundsFunctionArguments* args) {
    const auto* spheres = static_cast<const LeafSphere*>(args->geometryUserPtr);
    const LeafSphere& s = spheres[args->primID];
    // Padded so float rounding never culls a sphere the double-precision chord would hit.
    auto pad = [&](double c) { return s.radius * (1 + 1e-6) + 1e-6 * (1 + std::abs(c)); };
    RTCBounds* b = args->bounds_o;
    b->lower_x = static_cast<float>(s.center.x - pad(s.center.x));
    b->lower_y = static_cast<float>(s.center.y - pad(s.center.y));
    b->lower_z = static_cast<float>(s.center.z - pad(s.center.z));
    b->upper_x = static_cast<float>(s.center.x + pad(s.center.x));
    b->upper_y = static_cast<float>(s.center.y + pad(s.center.y));
    b->upper_z = static_cast<float>(s.center.z + pad(s.center.z));
}

// Every sphere the ray meets adds its chord; the ray is only reported occluded once the
// direction is dark (the cap), which ends its traversal early. Each primitive is visited at
// most once per ray (user geometry is not split), and integer sums do not care about order.
void sphereOccluded(const RTCOccludedFunctionNArguments* args) {
    auto* ctx = reinterpret_cast<LightRayContext*>(args->context);
    if (args->primID == ctx->self) return;
    const LeafSphere& s = ctx->spheres[args->primID];
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i]) continue;
        unsigned k = RTCRayN_id(args->ray, args->N, i);
        int64_t q = chordQuanta(ctx->origin, ctx->dome->directions[k], s);
        if (q == 0) continue;
        ctx->quanta[k] += q;
        if (ctx->quanta[k] >= ctx->cap)
            RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
    }
}

}  // namespace

LeafLightTracer::LeafLightTracer() : device_(std::make_unique<Device>()) {
    device_->device = rtcNewDevice(nullptr);
    if (!device_->device) throw std::runtime_error("Embree: cannot create device");
}

LeafLightTracer::~LeafLightTracer() { rtcReleaseDevice(device_->device); }

std::vector<SphereLight> LeafLightTracer::compute(const std::vector<LeafSphere>& spheres,
                                                  const SkyDome& dome,
                                                  const LeafLightParameters& p) const {
    size_t n = spheres.size(), K = dome.directions.size();
    if (n == 0 || p.extinction <= 0) return leafLightReference(spheres, dome, p);
    RTCScene scene = rtcNewScene(device_->device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry geom = rtcNewGeometry(device_->device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(n));
    rtcSetGeometryUserData(geom, const_cast<LeafSphere*>(spheres.data()));
    rtcSetGeometryBoundsFunction(geom, sphereBounds, const_cast<LeafSphere*>(spheres.data()));
    rtcSetGeometryOccludedFunction(geom, sphereOccluded);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    if (rtcGetDeviceError(device_->device) != RTC_ERROR_NONE) {
        rtcReleaseScene(scene);
        throw std::runtime_error("Embree: building the leaf-sphere BVH failed");
    }

    std::vector<SphereLight> out(n);
    int64_t cap = quantaCap(p.extinction);
    forEachSphere(n, p.threads, [&](const tbb::blocked_range<size_t>& range) {
        std::vector<int64_t> quanta(K);
        LightRayContext ctx;
        rtcInitIntersectContext(&ctx.context);
        ctx.spheres = spheres.data();
        ctx.dome = &dome;
        ctx.cap = cap;
        ctx.quanta = quanta.data();
        for (size_t i = range.begin(); i != range.end(); ++i) {
            std::fill(quanta.begin(), quanta.end(), 0);
            ctx.origin = spheres[i].center;
            ctx.self = static_cast<uint32_t>(i);
            if (!p.packets) {
                for (size_t k = 0; k < K; ++k) {
                    const Vec3& d = dome.directions[k];
                    alignas(16) RTCRay ray;
                    ray.org_x = static_cast<float>(ctx.origin.x);
                    ray.org_y = static_cast<float>(ctx.origin.y);
                    ray.org_z = static_cast<float>(ctx.origin.z);
                    ray.dir_x = static_cast<float>(d.x);
                    ray.dir_y = static_cast<float>(d.y);
                    ray.dir_z = static_cast<float>(d.z);
                    ray.tnear = 0;
                    ray.tfar = std::numeric_limits<float>::infinity();
                    ray.time = 0;
                    ray.mask = 0xffffffffu;
                    ray.id = static_cast<unsigned>(k);
                    ray.flags = 0;
                    rtcOccluded1(scene, &ctx.context, &ray);
                }
            }
            for (size_t k0 = 0; p.packets && k0 < K; k0 += 16) {
                alignas(64) RTCRay16 rays;
                alignas(64) int valid[16];
                for (int l = 0; l < 16; ++l) {
                    size_t k = k0 + l;
                    valid[l] = k < K ? -1 : 0;
                    const Vec3& d = dome.directions[k < K ? k : 0];
                    rays.org_x[l] = static_cast<float>(ctx.origin.x);
                    rays.org_y[l] = static_cast<float>(ctx.origin.y);
                    rays.org_z[l] = static_cast<float>(ctx.origin.z);
                    rays.dir_x[l] = static_cast<float>(d.x);
                    rays.dir_y[l] = static_cast<float>(d.y);
                    rays.dir_z[l] = static_cast<float>(d.z);
                    rays.tnear[l] = 0;
                    rays.tfar[l] = std::numeric_limits<float>::infinity();
                    rays.time[l] = 0;
                    rays.mask[l] = 0xffffffffu;
                    rays.id[l] = static_cast<unsigned>(k < K ? k : 0);
                    rays.flags[l] = 0;
                }
                rtcOccluded16(valid, scene, &ctx.context, &rays);
            }
            for (int64_t& q : quanta) q = std::min(q, cap);
            out[i] = finishLight(quanta, dome, p);
        }
    });
    rtcReleaseScene(scene);
    return out;
}

}  // namespace nenrin
