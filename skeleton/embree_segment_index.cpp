// The only file that talks to Embree for skeleton queries (see docs/design/embree.md):
// curves get no point-query callbacks, so segments are user geometry with a bounds function,
// and the point-query callback computes the exact distance in double precision with the same
// function as the brute-force reference.

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "skeleton/segment_geometry.h"
#include "skeleton/segment_index.h"

namespace nenrin {

namespace {

struct QueryState {
    const SegmentSoup* soup;
    Vec3 p;
    // nearest
    NearestSegment best;
    // gather
    double radius2 = 0;
    std::vector<uint32_t>* out = nullptr;
};

void segmentBounds(const RTCBoundsFunctionArguments* args) {
    const auto* soup = static_cast<const SegmentSoup*>(args->geometryUserPtr);
    const Vec3& a = soup->a[args->primID];
    const Vec3& b = soup->b[args->primID];
    const double r = soup->radius.empty() ? 0.0 : soup->radius[args->primID];
    // Pad by a relative epsilon so float rounding never culls a segment the double-precision
    // distance would accept.
    auto lo = [r](double u, double v) {
        double m = std::min(u, v) - r;
        return static_cast<float>(m - 1e-6 * (1 + std::abs(m)));
    };
    auto hi = [r](double u, double v) {
        double m = std::max(u, v) + r;
        return static_cast<float>(m + 1e-6 * (1 + std::abs(m)));
    };
    RTCBounds* box = args->bounds_o;
    box->lower_x = lo(a.x, b.x);
    box->lower_y = lo(a.y, b.y);
    box->lower_z = lo(a.z, b.z);
    box->upper_x = hi(a.x, b.x);
    box->upper_y = hi(a.y, b.y);
    box->upper_z = hi(a.z, b.z);
}

float paddedRadius(double r) {
    // Covers the float rounding of the query point (|p| up to ~100 m) and of the radius.
    return static_cast<float>(r * (1 + 1e-6) + 1e-5);
}

bool nearestCallback(RTCPointQueryFunctionArguments* args) {
    auto* st = static_cast<QueryState*>(args->userPtr);
    uint32_t prim = args->primID;
    double d2 = soupDistance2(*st->soup, prim, st->p);
    int32_t id = static_cast<int32_t>(st->soup->ids[prim]);
    if (d2 < st->best.distance2 || (d2 == st->best.distance2 && id < st->best.segment)) {
        st->best.distance2 = d2;
        st->best.segment = id;
        args->query->radius = paddedRadius(std::sqrt(d2));
        return true;
    }
    return false;
}

bool gatherCallback(RTCPointQueryFunctionArguments* args) {
    auto* st = static_cast<QueryState*>(args->userPtr);
    uint32_t prim = args->primID;
    if (soupDistance2(*st->soup, prim, st->p) <= st->radius2)
        st->out->push_back(st->soup->ids[prim]);
    return false;
}

class EmbreeSegmentIndex final : public SegmentIndex {
public:
    explicit EmbreeSegmentIndex(SegmentSoup soup) : soup_(std::move(soup)) {
        device_ = rtcNewDevice(nullptr);
        if (!device_) throw std::runtime_error("Embree: cannot create device");
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
        if (!soup_.ids.empty()) {
            RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_USER);
            rtcSetGeometryUserPrimitiveCount(geom, static_cast<unsigned>(soup_.ids.size()));
            rtcSetGeometryUserData(geom, &soup_);
            rtcSetGeometryBoundsFunction(geom, segmentBounds, &soup_);
            rtcCommitGeometry(geom);
            rtcAttachGeometry(scene_, geom);
            rtcReleaseGeometry(geom);
        }
        rtcCommitScene(scene_);
        if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
            throw std::runtime_error("Embree: building the segment BVH failed");
    }

    ~EmbreeSegmentIndex() override {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }

    NearestSegment nearest(const Vec3& p, double maxRadius) const override {
        QueryState st;
        st.soup = &soup_;
        st.p = p;
        if (soup_.ids.empty()) return st.best;
        alignas(16) RTCPointQuery query;
        query.x = static_cast<float>(p.x);
        query.y = static_cast<float>(p.y);
        query.z = static_cast<float>(p.z);
        query.time = 0;
        query.radius = std::isfinite(maxRadius) ? paddedRadius(maxRadius)
                                                : std::numeric_limits<float>::infinity();
        alignas(16) RTCPointQueryContext context;
        rtcInitPointQueryContext(&context);
        rtcPointQuery(scene_, &query, &context, nearestCallback, &st);
        if (st.best.distance2 > maxRadius * maxRadius) return NearestSegment{};
        return st.best;
    }

    void gather(const Vec3& p, double radius, std::vector<uint32_t>& out) const override {
        if (soup_.ids.empty()) return;
        QueryState st;
        st.soup = &soup_;
        st.p = p;
        st.radius2 = radius * radius;
        st.out = &out;
        alignas(16) RTCPointQuery query;
        query.x = static_cast<float>(p.x);
        query.y = static_cast<float>(p.y);
        query.z = static_cast<float>(p.z);
        query.time = 0;
        query.radius = paddedRadius(radius);
        alignas(16) RTCPointQueryContext context;
        rtcInitPointQueryContext(&context);
        rtcPointQuery(scene_, &query, &context, gatherCallback, &st);
    }

    size_t size() const override { return soup_.ids.size(); }

private:
    SegmentSoup soup_;
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
};

}  // namespace

std::unique_ptr<SegmentIndex> makeEmbreeSegmentIndex(SegmentSoup soup) {
    return std::make_unique<EmbreeSegmentIndex>(std::move(soup));
}

}  // namespace nenrin
