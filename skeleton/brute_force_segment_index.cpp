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

namespace {

class BruteForceSegmentIndex final : public SegmentIndex {
public:
    explicit BruteForceSegmentIndex(SegmentSoup soup) : soup_(std::move(soup)) {}

    NearestSegment nearest(const Vec3& p, double maxRadius) const override {
        NearestSegment best;
        double limit2 = maxRadius * maxRadius;
        for (size_t i = 0; i < soup_.ids.size(); ++i) {
            double d2 = projectOntoSegment(p, soup_.a[i], soup_.b[i]).distance2;
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
            if (projectOntoSegment(p, soup_.a[i], soup_.b[i]).distance2 <= r2)
                out.push_back(soup_.ids[i]);
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
