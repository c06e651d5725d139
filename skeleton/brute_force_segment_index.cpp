#include <algorithm>
#include <cmath>

#include "skeleton/segment_geometry.h"
#include "skeleton/segment_index.h"

namespace nenrin {

SegmentSoup collectSegments(const Skeleton& skeleton, SegmentKind kind) {
    SegmentSoup soup;
    for (uint32_t i = 0; i < skeleton.segments().size(); ++i) {
        const auto& s = skeleton.segment(i);
        if (s.kind != kind) continue;
        soup.a.push_back(skeleton.start(s));
        soup.b.push_back(skeleton.end(s));
        soup.ids.push_back(i);
    }
    return soup;
}

SegmentSoup collectChainPieces(const Skeleton& skeleton, uint32_t runLength) {
    SegmentSoup soup;
    for (uint32_t c = 0; c < skeleton.chains().size(); ++c) {
        const SkeletonChain& chain = skeleton.chain(c);
        if (chain.kind != SegmentKind::Branch) continue;
        const uint32_t end = chain.firstSegment + chain.segmentCount;
        for (uint32_t first = chain.firstSegment; first < end; first += runLength) {
            const uint32_t last = std::min(end, first + runLength);
            const Vec3 a = skeleton.start(skeleton.segment(first));
            const Vec3 b = skeleton.end(skeleton.segment(last - 1));
            // Every joint within the radius of the axis, so every segment (the capsule is
            // convex); rounded up well past the rounding of any distance at tree scale.
            double radius2 = 0;
            for (uint32_t s = first; s < last; ++s) {
                const auto& seg = skeleton.segment(s);
                for (const Vec3& q : {skeleton.start(seg), skeleton.end(seg)})
                    radius2 = std::max(radius2, projectOntoSegment(q, a, b).distance2);
            }
            soup.a.push_back(a);
            soup.b.push_back(b);
            soup.ids.push_back(c);
            soup.radius.push_back(std::sqrt(radius2) * (1 + 1e-9) + 1e-9);
        }
    }
    return soup;
}

double soupDistance2(const SegmentSoup& soup, size_t i, const Vec3& p) {
    const double d2 = projectOntoSegment(p, soup.a[i], soup.b[i]).distance2;
    if (soup.radius.empty()) return d2;
    const double d = std::max(0.0, std::sqrt(d2) - soup.radius[i]);
    return d * d;
}

namespace {

class BruteForceSegmentIndex final : public SegmentIndex {
public:
    explicit BruteForceSegmentIndex(SegmentSoup soup) : soup_(std::move(soup)) {}

    NearestSegment nearest(const Vec3& p, double maxRadius) const override {
        NearestSegment best;
        double limit2 = maxRadius * maxRadius;
        for (size_t i = 0; i < soup_.ids.size(); ++i) {
            double d2 = soupDistance2(soup_, i, p);
            if (d2 > limit2) continue;
            int32_t id = static_cast<int32_t>(soup_.ids[i]);
            if (d2 < best.distance2 || (d2 == best.distance2 && id < best.segment)) {
                best.distance2 = d2;
                best.segment = id;
            }
        }
        return best;
    }

    void gather(const Vec3& p, double radius, std::vector<uint32_t>& out) const override {
        double r2 = radius * radius;
        for (size_t i = 0; i < soup_.ids.size(); ++i)
            if (soupDistance2(soup_, i, p) <= r2) out.push_back(soup_.ids[i]);
    }

    size_t size() const override { return soup_.ids.size(); }

private:
    SegmentSoup soup_;
};

}  // namespace

std::unique_ptr<SegmentIndex> makeBruteForceSegmentIndex(SegmentSoup soup) {
    return std::make_unique<BruteForceSegmentIndex>(std::move(soup));
}

}  // namespace nenrin
