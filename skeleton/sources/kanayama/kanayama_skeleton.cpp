#include "skeleton/sources/kanayama/kanayama_skeleton.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>

namespace nenrin {

namespace {

double radiusOf(double area) { return std::sqrt(area / std::numbers::pi); }

}  // namespace

Skeleton buildKanayamaSkeleton(const std::vector<KanayamaShoot>& shoots,
                               const std::vector<double>& trunkBaseRadius,
                               const KanayamaSpecies& species) {
    Skeleton skeleton;
    if (shoots.empty() || shoots[0].removed) return skeleton;
    size_t n = shoots.size();
    std::vector<int32_t> continuation(n, kNone);
    std::vector<std::vector<int32_t>> laterals(n);
    for (size_t i = 1; i < n; ++i) {
        const KanayamaShoot& sh = shoots[i];
        if (sh.removed) continue;
        if (sh.terminal)
            continuation[sh.parent] = static_cast<int32_t>(i);
        else
            laterals[sh.parent].push_back(static_cast<int32_t>(i));
    }
    // Where each shoot's nodes landed: segment ending at node k of shoot s = segmentBase[s] + k.
    std::vector<int64_t> segmentBase(n, -1);
    double radius0 = radiusOf(species.initialArea);
    int lastYear = static_cast<int>(trunkBaseRadius.size()) - 1;
    auto trunkRadiusAt = [&](int year) {  // at the end of `year`; -1 = the seedling's start
        if (year < 0 || trunkBaseRadius.empty()) return radius0;
        return trunkBaseRadius[std::min(year, lastYear)];
    };

    // Chains in breadth-first order, so every parent chain exists before its branches.
    std::deque<int32_t> heads{0};
    while (!heads.empty()) {
        int32_t head = heads.front();
        heads.pop_front();
        std::vector<Vec3> points{shoots[head].nodes.front()};
        std::vector<double> times{static_cast<double>(shoots[head].year)};
        std::vector<double> radii{radiusOf(shoots[head].area)};
        std::vector<int32_t> members;
        for (int32_t s = head; s != kNone; s = continuation[s]) {
            const KanayamaShoot& sh = shoots[s];
            int m = static_cast<int>(sh.nodes.size()) - 1;
            segmentBase[s] = static_cast<int64_t>(skeleton.segments().size()) +
                             static_cast<int64_t>(points.size()) - 2;
            for (int k = 1; k <= m; ++k) {
                points.push_back(sh.nodes[k]);
                times.push_back(sh.year + species.seasonFraction * k / m);
                radii.push_back(radiusOf(sh.area));
            }
            members.push_back(s);
        }
        if (head == 0) {
            skeleton.addTrunk(points, times, radii);
        } else {
            const KanayamaShoot& base = shoots[head];
            ChainProperties props;
            props.diebackExponent = 1;
            props.deathTime = base.deathTime;
            // Radial growth of the branch base against the trunk base over the same years.
            int endYear = std::isfinite(base.deathTime)
                              ? static_cast<int>(std::ceil(base.deathTime)) - 1
                              : lastYear;
            endYear = std::max(endYear, base.year);
            double branch = radiusOf(base.area) - radius0;
            double trunk = trunkRadiusAt(endYear) - trunkRadiusAt(base.year - 1);
            props.gamma = std::clamp(trunk > 0 ? branch / trunk : 1.0, 0.02, 2.0);
            int64_t parentSegment = segmentBase[base.parent] + base.parentNode;
            skeleton.addBranch(static_cast<uint32_t>(parentSegment), points, times, props, radii);
        }
        for (int32_t s : members)
            for (int32_t child : laterals[s]) heads.push_back(child);
    }
    std::vector<double> rings;
    double previous = 0;
    for (double r : trunkBaseRadius) {
        rings.push_back(r - previous);
        previous = r;
    }
    skeleton.setRingWidths(std::move(rings));
    return skeleton;
}

}  // namespace nenrin
