#include "renderer/preview/tree_preview.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "renderer/parallel_tiles.h"
#include "util/hash.h"

namespace nenrin {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180;
constexpr double kFovY = 30 * kDegree;
constexpr unsigned kGroundId = 1;

struct Rgb {
    double r, g, b;
};
constexpr Rgb kBark{0.20, 0.13, 0.08}, kDeadWood{0.30, 0.29, 0.27}, kGround{0.16, 0.17, 0.12};
constexpr Rgb kSkyZenith{0.35, 0.55, 0.95}, kSkyHorizon{0.85, 0.9, 1.0}, kSun{2.4, 2.3, 2.1};

/// Embree scene holding the curves and the ground disc (two triangles would do, but a disc
/// is easier to read in the picture: a big quad clipped by distance in the shader).
class CurveScene {
public:
    CurveScene(const Skeleton& sk, const std::vector<float>& radii, Vec3 groundCentre,
               double groundRadius) {
        device_ = rtcNewDevice(nullptr);
        if (!device_) throw std::runtime_error("embree: could not create a device");
        scene_ = rtcNewScene(device_);
        RTCGeometry curves = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(curves, RTC_BUFFER_TYPE_VERTEX, 0,
                                                              RTC_FORMAT_FLOAT4, 4 * sizeof(float),
                                                              sk.nodes().size()));
        for (size_t i = 0; i < sk.nodes().size(); ++i) {
            const Vec3& p = sk.node(i).position;
            v[4 * i] = float(p.x), v[4 * i + 1] = float(p.y), v[4 * i + 2] = float(p.z);
            v[4 * i + 3] = radii[i];
        }
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(curves, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT,
                                    sizeof(unsigned), sk.segments().size()));
        // A segment's nodes are consecutive (Skeleton stores each chain's nodes in order).
        for (size_t i = 0; i < sk.segments().size(); ++i) idx[i] = sk.segment(i).from;
        rtcCommitGeometry(curves);
        rtcAttachGeometryByID(scene_, curves, 0);
        rtcReleaseGeometry(curves);

        RTCGeometry ground = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* gv = static_cast<float*>(rtcSetNewGeometryBuffer(
            ground, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
        double r = groundRadius;
        const double corners[4][2] = {{-r, -r}, {r, -r}, {r, r}, {-r, r}};
        for (int i = 0; i < 4; ++i) {
            gv[3 * i] = float(groundCentre.x + corners[i][0]);
            gv[3 * i + 1] = float(groundCentre.y + corners[i][1]);
            gv[3 * i + 2] = float(groundCentre.z);
        }
        auto* gi = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            ground, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), 2));
        const unsigned tris[6] = {0, 1, 2, 0, 2, 3};
        std::copy(tris, tris + 6, gi);
        rtcCommitGeometry(ground);
        rtcAttachGeometryByID(scene_, ground, kGroundId);
        rtcReleaseGeometry(ground);
        rtcCommitScene(scene_);
    }
    ~CurveScene() {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }
    CurveScene(const CurveScene&) = delete;
    CurveScene& operator=(const CurveScene&) = delete;

    bool intersect(const Vec3& o, const Vec3& d, RTCRayHit& rh) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        rh = {};
        rh.ray.org_x = float(o.x), rh.ray.org_y = float(o.y), rh.ray.org_z = float(o.z);
        rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
        rh.ray.tfar = std::numeric_limits<float>::infinity();
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &rh);
        return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }

    bool occluded(const Vec3& o, const Vec3& d) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay ray{};
        ray.org_x = float(o.x), ray.org_y = float(o.y), ray.org_z = float(o.z);
        ray.dir_x = float(d.x), ray.dir_y = float(d.y), ray.dir_z = float(d.z);
        ray.tnear = 0;
        ray.tfar = std::numeric_limits<float>::infinity();
        ray.mask = ~0u;
        rtcOccluded1(scene_, &context, &ray);
        return ray.tfar < 0;
    }

private:
    RTCDevice device_;
    RTCScene scene_;
};

Rgb sky(const Vec3& d) {
    double t = std::clamp(d.z, 0.0, 1.0);
    return {kSkyHorizon.r + (kSkyZenith.r - kSkyHorizon.r) * t,
            kSkyHorizon.g + (kSkyZenith.g - kSkyHorizon.g) * t,
            kSkyHorizon.b + (kSkyZenith.b - kSkyHorizon.b) * t};
}

/// The view of the whole tree: its nodes' bounding box seen from (azimuth, elevation).
struct TreeView {
    Vec3 lo, hi, centre;
    Vec3 eye, forward, right, up;
    double aspect, tanHalf, distance;
    double ground;  ///< radius of the ground disc
};

TreeView frameTree(const Skeleton& sk, const TreePreviewOptions& o) {
    TreeView v;
    v.lo = {1e300, 1e300, 1e300};
    v.hi = {-1e300, -1e300, -1e300};
    for (const auto& n : sk.nodes()) {
        v.lo = {std::min(v.lo.x, n.position.x), std::min(v.lo.y, n.position.y),
                std::min(v.lo.z, n.position.z)};
        v.hi = {std::max(v.hi.x, n.position.x), std::max(v.hi.y, n.position.y),
                std::max(v.hi.z, n.position.z)};
    }
    const Vec3 &lo = v.lo, &hi = v.hi;
    v.centre = (lo + hi) * 0.5;
    v.aspect = double(o.width) / o.height;
    // Fit the tree's height and width (trees are tall: a bounding sphere would leave most of
    // a portrait frame empty), standing back by the crown's half width.
    double halfHeight = std::max(0.5 * (hi.z - lo.z), 0.05);
    double halfWidth = std::max(0.5 * std::max(hi.x - lo.x, hi.y - lo.y), 0.05);
    double tanY = std::tan(0.5 * kFovY), tanX = tanY * v.aspect;
    v.distance = 1.12 * std::max(halfHeight / tanY, halfWidth / tanX) + halfWidth;
    v.ground = std::max(1.6 * halfWidth, 0.6 * halfHeight);
    Vec3 toCamera{std::cos(o.elevation * kDegree) * std::cos(o.azimuth * kDegree),
                  std::cos(o.elevation * kDegree) * std::sin(o.azimuth * kDegree),
                  std::sin(o.elevation * kDegree)};
    v.eye = v.centre + toCamera * v.distance;
    v.forward = normalize(v.centre - v.eye);
    v.right = normalize(cross(v.forward, Vec3{0, 0, 1}));
    v.up = cross(v.right, v.forward);
    v.tanHalf = std::tan(0.5 * kFovY);
    return v;
}

/// Radii: the skeleton's, or from the node's age; never thinner than half a pixel.
std::vector<float> previewRadii(const Skeleton& sk, const TreePreviewOptions& o,
                                const TreeView& view, bool& estimated) {
    double lastBirth = 0;
    bool anyRadius = false;
    for (const auto& n : sk.nodes()) {
        lastBirth = std::max(lastBirth, n.birthTime);
        anyRadius = anyRadius || n.radius > 0;
    }
    estimated = !anyRadius;
    const double pixelAngle = 2 * view.tanHalf / o.height;
    double age = lastBirth + 1;
    std::vector<float> radii(sk.nodes().size());
    std::vector<double> gammaOfNode(sk.nodes().size(), 1.0);
    for (const auto& s : sk.segments()) gammaOfNode[s.to] = s.gamma, gammaOfNode[s.from] = s.gamma;
    for (size_t i = 0; i < radii.size(); ++i) {
        const SkeletonNode& n = sk.node(i);
        double r = anyRadius ? n.radius
                             : o.radiusPerYear * gammaOfNode[i] * std::max(0.0, age - n.birthTime);
        double minimum = 0.5 * pixelAngle * length(n.position - view.eye);
        radii[i] = float(std::max(r, minimum));
    }
    return radii;
}

/// The radiance along one camera ray: sky, the ground disc or the tree, under sun and sky.
Rgb previewRadiance(const Skeleton& sk, const CurveScene& scene, const TreeView& view,
                    const Vec3& sun, const Vec3& d) {
    RTCRayHit rh;
    if (!scene.intersect(view.eye, d, rh)) return sky(d);
    Vec3 p = view.eye + d * double(rh.ray.tfar);
    Vec3 n = normalize(Vec3{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z});
    if (dot(n, d) > 0) n = n * -1.0;
    Rgb albedo = kGround;
    if (rh.hit.geomID == kGroundId) {
        // Fade the ground square into the sky: a disc around the tree.
        double r = length(Vec3{p.x - view.centre.x, p.y - view.centre.y, 0}) / view.ground;
        if (r > 1) return sky(d);
    } else {
        const SkeletonSegment& seg = sk.segment(rh.hit.primID);
        albedo = std::isfinite(seg.deathTime) ? kDeadWood : kBark;
    }
    double lit = std::max(0.0, dot(n, sun));
    if (lit > 0 && scene.occluded(p + n * (1e-4 * view.distance), sun)) lit = 0;
    double skyLight = 0.35 * (0.6 + 0.4 * n.z);
    return {albedo.r * (kSun.r * lit + kSkyHorizon.r * skyLight),
            albedo.g * (kSun.g * lit + kSkyHorizon.g * skyLight),
            albedo.b * (kSun.b * lit + kSkyHorizon.b * skyLight)};
}

}  // namespace

TreePreview renderTreePreview(const Skeleton& sk, const TreePreviewOptions& o) {
    if (sk.empty()) throw std::invalid_argument("renderTreePreview: empty skeleton");
    TreePreview out;
    out.width = o.width, out.height = o.height;
    out.segments = sk.segments().size();
    const TreeView view = frameTree(sk, o);
    const std::vector<float> radii = previewRadii(sk, o, view, out.estimatedRadii);
    CurveScene scene(sk, radii, {view.centre.x, view.centre.y, view.lo.z}, view.ground);
    Vec3 sun = normalize(
        Vec3{std::cos((o.azimuth + 70) * kDegree), std::sin((o.azimuth + 70) * kDegree), 1.1});

    out.rgb.assign(size_t(o.width) * o.height * 3, 0.f);
    const int spp = std::max(1, o.spp);
    int strata = static_cast<int>(std::ceil(std::sqrt(double(spp))));
    parallelTiles(static_cast<size_t>(o.height), o.threads, [&](size_t row) {
        int y = static_cast<int>(row);
        for (int x = 0; x < o.width; ++x) {
            Rgb sum{0, 0, 0};
            uint64_t pixel = uint64_t(y) * uint64_t(o.width) + uint64_t(x);
            for (int s = 0; s < spp; ++s) {
                double jx = ((s % strata) + uniform01(7, pixel, 2 * s)) / strata;
                double jy = ((s / strata % strata) + uniform01(7, pixel, 2 * s + 1)) / strata;
                double u = (2 * (x + jx) / o.width - 1) * view.tanHalf * view.aspect;
                double v = (1 - 2 * (y + jy) / o.height) * view.tanHalf;
                Vec3 d = normalize(view.forward + view.right * u + view.up * v);
                Rgb c = previewRadiance(sk, scene, view, sun, d);
                sum = {sum.r + c.r, sum.g + c.g, sum.b + c.b};
            }
            float* px = &out.rgb[(size_t(y) * o.width + x) * 3];
            px[0] = float(sum.r / spp), px[1] = float(sum.g / spp), px[2] = float(sum.b / spp);
        }
    });
    return out;
}

}  // namespace nenrin
