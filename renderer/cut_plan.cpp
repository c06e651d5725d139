#include "renderer/cut_plan.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "renderer/bake_specs.h"
#include "util/hash.h"

namespace nenrin {

void trunkHeightRange(const Skeleton& skeleton, double& lo, double& hi) {
    const SkeletonChain& trunk = skeleton.chain(0);
    lo = skeleton.start(skeleton.segment(trunk.firstSegment)).z;
    hi = skeleton.end(skeleton.segment(trunk.firstSegment + trunk.segmentCount - 1)).z;
}

double logRadius(const GrowthField& field, const CutPlanParams& params, double z, double theta) {
    const double felled = field.params().fellingTime;
    if (felled <= 0) return params.maxRadius;
    Vec3 pith = pithAtHeight(field.skeleton(), z);
    Vec3 dir{std::cos(theta), std::sin(theta), 0};
    // T grows outwards from the pith; the bark is where it reaches the felling time. A knot
    // can make T non-monotonic along the ray, so keep the first crossing found by stepping
    // before bisecting.
    double step = 0.01, r0 = 0, r1 = step;
    while (r1 < 2.0 && field.evaluate(pith + dir * r1).T <= felled) {
        r0 = r1;
        r1 += step;
    }
    if (r1 >= 2.0) return 2.0;
    for (int i = 0; i < 24; ++i) {
        double m = 0.5 * (r0 + r1);
        (field.evaluate(pith + dir * m).T <= felled ? r0 : r1) = m;
    }
    return r0;
}

std::optional<BoardCut> cutBoard(const GrowthField& field, const CutPlanParams& params,
                                 double length, double width, double thickness, uint64_t index) {
    double trunkLo, trunkHi;
    trunkHeightRange(field.skeleton(), trunkLo, trunkHi);
    double bottom = std::max(params.bottom, trunkLo);
    double top = params.top > 0 ? params.top : trunkLo + 0.7 * (trunkHi - trunkLo);
    if (top - bottom < length) return std::nullopt;

    SplitMix rng(hashCombine(params.seed, 0xb0a7d000ull + index));
    for (int attempt = 0; attempt < 64; ++attempt) {
        BoardCut cut;
        cut.height = rng.uniform(bottom + 0.5 * length, top - 0.5 * length);
        cut.azimuth = rng.uniform(0, 2 * std::numbers::pi);
        cut.quarterSawn = params.sawing == Sawing::Quarter ||
                          (params.sawing == Sawing::Mixed && rng.uniform() < 0.5);
        bool flipFace = rng.uniform() < 0.5, flipEnd = rng.uniform() < 0.5;
        double u = rng.uniform();

        // The smallest log radius along the board and across its corners' azimuths.
        double reach = 0;
        for (int k = 0; k < 5; ++k) {
            double z = cut.height + length * (k / 4.0 - 0.5);
            for (double dTheta : {-0.5, 0.0, 0.5}) {
                double r = logRadius(field, params, z, cut.azimuth + dTheta);
                reach = k == 0 && dTheta == -0.5 ? r : std::min(reach, r);
            }
        }
        reach -= params.margin;
        // Corners of the cross-section relative to the pith, in (radial, tangential) terms.
        double radialHalf = cut.quarterSawn ? 0.5 * width : 0.5 * thickness;
        double tangentialHalf = cut.quarterSawn ? 0.5 * thickness : 0.5 * width;
        if (reach <= tangentialHalf) continue;
        double maxOffset = std::sqrt(reach * reach - tangentialHalf * tangentialHalf) - radialHalf;
        // Quarter-sawn boards stay on one side of the pith.
        double minOffset = cut.quarterSawn ? radialHalf : 0.0;
        if (maxOffset < minOffset) continue;
        cut.offset = minOffset + u * (maxOffset - minOffset);

        Vec3 radial{std::cos(cut.azimuth), std::sin(cut.azimuth), 0};
        Vec3 tangential{-radial.y, radial.x, 0};
        Vec3 along{0, 0, flipEnd ? -1.0 : 1.0};
        Vec3 widthAxis = cut.quarterSawn ? radial : tangential;
        if (flipFace) widthAxis = -widthAxis;
        Vec3 centre = pithAtHeight(field.skeleton(), cut.height) + radial * cut.offset;
        cut.treeFromLamella =
            RigidTransform::fromAxes(along, widthAxis, cross(along, widthAxis), centre);
        return cut;
    }
    return std::nullopt;
}

}  // namespace nenrin
