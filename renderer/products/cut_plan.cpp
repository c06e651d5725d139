#include "renderer/products/cut_plan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "util/hash.h"
#include "util/random_draws.h"

namespace nenrin {

void trunkHeightRange(const Skeleton& skeleton, double& lo, double& hi) {
    const SkeletonChain& trunk = skeleton.chain(0);
    lo = skeleton.start(skeleton.segment(trunk.firstSegment)).z;
    hi = skeleton.end(skeleton.segment(trunk.firstSegment + trunk.segmentCount - 1)).z;
}

double logRadius(const GrowthField& field, const CutPlanParams& params, double z, double theta) {
    const double felled = field.params().fellingTime;
    if (felled <= 0) return params.maxRadius;
    const Vec3 pith = pithAtHeight(field.skeleton(), z);
    const Vec3 dir{std::cos(theta), std::sin(theta), 0};
    // T grows outwards from the pith; the bark is where it first reaches the felling time (a
    // knot can make T non-monotonic further out). Three batched passes along the ray, each 32
    // times finer: 1 cm, 0.3 mm, 10 um; batches are far cheaper than single evaluations.
    constexpr int kSteps = 32;
    constexpr double kMaxRadius = 2.0;
    GrowthScratch scratch;
    std::vector<Vec3> points(kSteps + 1);
    std::vector<GrowthSample> samples(kSteps + 1);
    double lo = 0, step = 0.01;
    // Coarse pass: march out in runs of 32 centimetres until T passes the felling time.
    for (bool found = false; !found;) {
        for (int i = 0; i <= kSteps; ++i) points[i] = pith + dir * (lo + i * step);
        field.evaluateBatch(points, samples, scratch);
        for (int i = 1; i <= kSteps && !found; ++i) {
            if (samples[i].T > felled) {
                lo += (i - 1) * step;
                found = true;
            }
        }
        if (!found) {
            lo += kSteps * step;
            if (lo >= kMaxRadius) return kMaxRadius;
        }
    }
    for (int pass = 0; pass < 2; ++pass) {
        step /= kSteps;
        for (int i = 0; i <= kSteps; ++i) points[i] = pith + dir * (lo + i * step);
        field.evaluateBatch(points, samples, scratch);
        int i = 1;
        while (i < kSteps && samples[i].T <= felled) ++i;
        lo += (i - 1) * step;
    }
    return lo;
}

Rgb boardTint(const CutPlanParams& params, uint64_t index) {
    // Tree-to-tree variation of one species: lightness (sd ~4 %, about 1.5 L*) and warmth
    // (red up and blue down, sd ~2.5 %, about 1-2 in a* and b*).
    SplitMix rng(hashCombine(params.seed, 0x7ee5c010ull + index));
    const double v = params.colourVariation;
    const double light = std::exp(v * 0.04 * drawNormal(rng));
    const double warm = v * 0.025 * drawNormal(rng);
    return {light * (1 + warm), light, light * (1 - 1.5 * warm)};
}

std::optional<BoardCut> cutBoard(const GrowthField& field, const CutPlanParams& params,
                                 double length, double width, double thickness, uint64_t index) {
    double trunkLo, trunkHi;
    trunkHeightRange(field.skeleton(), trunkLo, trunkHi);
    double bottom = std::max(params.bottom, trunkLo);
    double top = params.top > 0 ? params.top : trunkLo + 0.7 * (trunkHi - trunkLo);
    if (top - bottom < length) return std::nullopt;

    SplitMix rng(hashCombine(params.seed, 0xb0a7d000ull + index));
    const Rgb tint = boardTint(params, index);
    for (int attempt = 0; attempt < 64; ++attempt) {
        BoardCut cut;
        cut.height = rng.uniform(bottom + 0.5 * length, top - 0.5 * length);
        cut.azimuth = rng.uniform(0, 2 * std::numbers::pi);
        cut.quarterSawn = params.sawing == Sawing::Quarter ||
                          (params.sawing == Sawing::Mixed && rng.uniform() < 0.5);
        bool flipFace = rng.uniform() < 0.5, flipEnd = rng.uniform() < 0.5;
        double u = rng.uniform();

        // Corners of the cross-section relative to the pith, in (radial, tangential) terms.
        double radialHalf = cut.quarterSawn ? 0.5 * width : 0.5 * thickness;
        double tangentialHalf = cut.quarterSawn ? 0.5 * thickness : 0.5 * width;
        // Quarter-sawn boards stay on one side of the pith.
        double minOffset = cut.quarterSawn ? radialHalf : 0.0;
        // The least log radius the board needs, at its smallest offset.
        double needed = std::hypot(minOffset + radialHalf, tangentialHalf) + params.margin;

        // The smallest log radius along the board and across its corners' azimuths; give up
        // on this position as soon as one is too small.
        double reach = std::numeric_limits<double>::infinity();
        for (int k = 0; k < 5 && reach >= needed; ++k) {
            double z = cut.height + length * (k / 4.0 - 0.5);
            for (double dTheta : {0.0, -0.5, 0.5}) {
                reach = std::min(reach, logRadius(field, params, z, cut.azimuth + dTheta));
                if (reach < needed) break;
            }
        }
        if (reach < needed) continue;
        reach -= params.margin;
        double maxOffset = std::sqrt(reach * reach - tangentialHalf * tangentialHalf) - radialHalf;
        cut.offset = minOffset + u * (maxOffset - minOffset);

        Vec3 radial{std::cos(cut.azimuth), std::sin(cut.azimuth), 0};
        Vec3 tangential{-radial.y, radial.x, 0};
        Vec3 along{0, 0, flipEnd ? -1.0 : 1.0};
        Vec3 widthAxis = cut.quarterSawn ? radial : tangential;
        if (flipFace) widthAxis = -widthAxis;
        Vec3 centre = pithAtHeight(field.skeleton(), cut.height) + radial * cut.offset;
        cut.treeFromLamella =
            RigidTransform::fromAxes(along, widthAxis, cross(along, widthAxis), centre);
        // The radius samples were a few azimuths: check the board's own edges against the bark
        // (corners and mid-edges of its cross-section at five stations along it).
        std::vector<Vec3> edge;
        for (int k = 0; k < 5; ++k)
            for (double a : {-0.5, 0.0, 0.5})
                for (double b : {-0.5, 0.5}) {
                    double x = length * (k / 4.0 - 0.5);
                    edge.push_back(
                        cut.treeFromLamella.point({x, width * a * 2 * 0.5, thickness * b}));
                    edge.push_back(
                        cut.treeFromLamella.point({x, width * b, thickness * a * 2 * 0.5}));
                }
        std::vector<GrowthSample> samples(edge.size());
        GrowthScratch scratch;
        field.evaluateBatch(edge, samples, scratch);
        bool inside = true;
        for (const GrowthSample& s : samples) inside = inside && s.T <= field.params().fellingTime;
        if (inside || field.params().fellingTime <= 0) {
            cut.tint = tint;
            return cut;
        }
    }
    return std::nullopt;
}

}  // namespace nenrin
