#include "skeleton/skeleton.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nenrin {

void Skeleton::addTrunk(const std::vector<Vec3>& points, const std::vector<double>& birthTimes,
                        const std::vector<double>& radii) {
    if (!chains_.empty()) throw std::logic_error("Skeleton::addTrunk: the trunk must come first");
    addChain(SegmentKind::Trunk, 0, kNone, kNone, points, birthTimes, radii, ChainProperties{});
}

uint32_t Skeleton::addBranch(uint32_t parentSegment, const std::vector<Vec3>& points,
                             const std::vector<double>& birthTimes, const ChainProperties& props,
                             const std::vector<double>& radii) {
    if (parentSegment >= segments_.size())
        throw std::logic_error("Skeleton::addBranch: parent segment out of range");
    const SkeletonSegment& parent = segments_[parentSegment];
    return addChain(SegmentKind::Branch, static_cast<uint8_t>(parent.order + 1),
                    static_cast<int32_t>(parent.chain), static_cast<int32_t>(parentSegment), points,
                    birthTimes, radii, props);
}

uint32_t Skeleton::addChain(SegmentKind kind, uint8_t order, int32_t parentChain,
                            int32_t parentSegment, const std::vector<Vec3>& points,
                            const std::vector<double>& birthTimes, const std::vector<double>& radii,
                            const ChainProperties& props) {
    if (points.size() < 2 || points.size() != birthTimes.size())
        throw std::logic_error("Skeleton: a chain needs >= 2 points with one birth time each");
    if (!radii.empty() && radii.size() != points.size())
        throw std::logic_error("Skeleton: radii must be empty or one per point");
    SkeletonChain chain;
    chain.kind = kind;
    chain.order = order;
    chain.parentChain = parentChain;
    chain.firstSegment = static_cast<uint32_t>(segments_.size());
    chain.segmentCount = static_cast<uint32_t>(points.size() - 1);
    uint32_t chainId = static_cast<uint32_t>(chains_.size());

    uint32_t firstNode = static_cast<uint32_t>(nodes_.size());
    for (size_t i = 0; i < points.size(); ++i)
        nodes_.push_back({points[i], birthTimes[i], radii.empty() ? 0.0 : radii[i]});
    for (uint32_t i = 0; i + 1 < points.size(); ++i) {
        SkeletonSegment s;
        s.from = firstNode + i;
        s.to = firstNode + i + 1;
        s.chain = chainId;
        s.kind = kind;
        s.order = order;
        uint32_t id = chain.firstSegment + i;
        s.previous = i == 0 ? kNone : static_cast<int32_t>(id - 1);
        s.next = i + 2 < points.size() ? static_cast<int32_t>(id + 1) : kNone;
        s.parent = i == 0 ? parentSegment : s.previous;
        s.gamma = kind == SegmentKind::Trunk ? 1.0 : props.gamma;
        s.deathTime = props.deathTime;
        s.diebackExponent = props.diebackExponent;
        segments_.push_back(s);
    }
    chains_.push_back(chain);
    return chainId;
}

double Skeleton::maxBranchGamma() const {
    double g = 0;
    for (const auto& s : segments_)
        if (s.kind == SegmentKind::Branch) g = std::max(g, s.gamma);
    return g;
}

Vec3 pithAtHeight(const Skeleton& skeleton, double z) {
    const SkeletonChain& trunk = skeleton.chain(0);
    for (uint32_t i = 0; i < trunk.segmentCount; ++i) {
        const auto& s = skeleton.segment(trunk.firstSegment + i);
        Vec3 a = skeleton.start(s), b = skeleton.end(s);
        if ((z - a.z) * (z - b.z) <= 0 && a.z != b.z) return lerp(a, b, (z - a.z) / (b.z - a.z));
    }
    const auto& first = skeleton.segment(trunk.firstSegment);
    const auto& last = skeleton.segment(trunk.firstSegment + trunk.segmentCount - 1);
    Vec3 lo = skeleton.start(first), hi = skeleton.end(last);
    Vec3 p = std::abs(z - lo.z) < std::abs(z - hi.z) ? lo : hi;
    return {p.x, p.y, z};
}

}  // namespace nenrin
