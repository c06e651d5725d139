/// GrowthField: its construction, and evaluateBatch, which runs its passes in order and hands
/// each the previous one's answer: the sway (here), the trunk (trunk_pass.cpp), the chain
/// culls (chain_culls.cpp) and the branches (branch_pass.cpp), over paths (path_time.cpp).

#include "grain/growth_field.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "grain/field_bounds.h"
#include "grain/field_passes.h"
#include "grain/field_rings.h"
#include "grain/growth_terms.h"

namespace nenrin {

namespace {

/// Points per group of chunks: branch chains are culled for each before its chunks, when the
/// tile has more candidate chains than kGroupCullAbove (with few, the culls cost more than
/// they save).
constexpr size_t kGroup = 4 * kChunk;
constexpr size_t kGroupCullAbove = 64;

/// The sway pass (section 4.5, main method): every point in the field's domain, displaced;
/// a run of `stencil` points by its first point's displacement (see evaluateBatch).
std::span<const Vec3> swayPoints(std::span<const Vec3> input, size_t stencil, const SwayWaves& sway,
                                 const WanderParams& wander, const WarpParams& warp,
                                 std::vector<Vec3>& swayed) {
    // The field's domain: beyond it squared distances overflow and no segment would be
    // nearest (once a crash). Farther points are evaluated as if on its edge, where the answer
    // is long settled (bark or beyond); NaN has no answer. Callers bound their inputs where
    // they read them; this keeps a missed case harmless.
    auto inDomain = [](const Vec3& p) {
        if (std::isnan(p.x) || std::isnan(p.y) || std::isnan(p.z))
            throw std::domain_error("growth field: a point with a NaN coordinate");
        if (std::abs(p.x) <= kFieldDomain && std::abs(p.y) <= kFieldDomain &&
            std::abs(p.z) <= kFieldDomain)
            return p;
        return Vec3{std::clamp(p.x, -kFieldDomain, kFieldDomain),
                    std::clamp(p.y, -kFieldDomain, kFieldDomain),
                    std::clamp(p.z, -kFieldDomain, kFieldDomain)};
    };
    const size_t n = input.size();
    swayed.resize(n);
    RingWander ringWander(wander);
    if (sway.amplitude == 0 && wander.amplitude == 0) {
        // Neither moves a point: only their zero sums are added, as below (-0 + 0 is +0). One
        // branch-free test of the whole batch first (NaN fails it too): usually all are inside.
        bool inside = true;
        for (const Vec3& p : input)
            inside &= (std::abs(p.x) <= kFieldDomain) & (std::abs(p.y) <= kFieldDomain) &
                      (std::abs(p.z) <= kFieldDomain);
        if (inside)
            for (size_t i = 0; i < n; ++i) swayed[i] = input[i] + Vec3{};
        else
            for (size_t i = 0; i < n; ++i) swayed[i] = inDomain(input[i]) + Vec3{};
    } else if (stencil <= 1 || n % stencil != 0) {
        for (size_t i = 0; i < n; ++i) {
            const Vec3 p = inDomain(input[i]);
            swayed[i] = p + swayDisplacement(p, sway) + ringWander(p);
        }
    } else {
        // The wander (and the warp below) are the rings' own small-scale shape: every point of
        // a stencil gets its own, so grad T (and the fibres) follow it.
        for (size_t i = 0; i < n; i += stencil) {
            const Vec3 d = swayDisplacement(inDomain(input[i]), sway);
            for (size_t j = i; j < i + stencil; ++j) {
                const Vec3 p = inDomain(input[j]);
                swayed[j] = p + d + ringWander(p);
            }
        }
    }
    // A measured warp (nenrin fit's) on top, where there is one: without, not even a zero is
    // added (-0 + 0 is +0, and the sign of a zero reaches atan2).
    if (warp.enabled())
        for (size_t i = 0; i < n; ++i) swayed[i] = swayed[i] + pointWarp(inDomain(input[i]), warp);
    return swayed;
}

double largest(std::span<const double> times) {
    double t = 0;
    for (const double x : times) t = std::max(t, x);
    return t;
}

}  // namespace

GrowthScratch::GrowthScratch() = default;
GrowthScratch::~GrowthScratch() = default;
GrowthScratch::GrowthScratch(const GrowthScratch&) {}
GrowthScratch& GrowthScratch::operator=(const GrowthScratch&) { return *this; }
GrowthScratch::GrowthScratch(GrowthScratch&&) noexcept = default;
GrowthScratch& GrowthScratch::operator=(GrowthScratch&&) noexcept = default;

GrowthBuffers& GrowthScratch::buffers() {
    if (!buffers_) buffers_ = std::make_unique<GrowthBuffers>();
    return *buffers_;
}

GrowthField::GrowthField(const SkeletonIndex& index, const GrainParams& params)
    : index_(&index), params_(params) {
    if (index.skeleton().empty() || index.trunk().size() == 0)
        throw std::invalid_argument("GrowthField: the skeleton has no trunk");
    sway_ = makeSwayWaves(params_.sway);
    segments_ = flattenSegments(index.skeleton());
    for (FieldSegment& f : segments_) f.inverseSpeed = 1 / (params_.radialSpeed * f.gamma);
    if (sway_.radialJitter != 0)
        for (const FieldSegment& f : segments_) swayFrames_.push_back(swayFrame(f.axis));
    taperLogOmega_ = std::log(params_.taper.omega);
    const Skeleton& sk = index.skeleton();
    chainTrees_ = ChainTrees(segments_, sk.chains(), index.backend() != IndexBackend::BruteForce);
    for (const SkeletonChain& c : sk.chains()) {
        const FieldSegment& first = segments_[c.firstSegment];
        ChainFrame f{first.a, first.axis, kInf, 0, 0, kInf};
        for (uint32_t i = c.firstSegment; i < c.firstSegment + c.segmentCount; ++i) {
            f.birthBound = std::min(f.birthBound, segments_[i].birthBound);
            f.gammaBound = std::max(f.gammaBound, segments_[i].gammaBound);
            f.deathBound = std::max(f.deathBound, segments_[i].deathBound);
            f.diebackBound = std::min(f.diebackBound, segments_[i].diebackBound);
        }
        chainFrames_.push_back(f);
    }
    maxGamma_ = index.skeleton().maxBranchGamma();
    // Largest radial speed any path can have (taper x direction x jitter): distance bounds.
    speedBound_ = params_.radialSpeed * (1 + params_.taper.nu) * (1 + params_.direction.strength) /
                  (1 - params_.sway.radialJitter);
    const FieldRings rings = fieldRingWidths(sk, params_);
    latewoodTiming_ = fieldLatewoodTiming(sk, rings, lateWoodShape(params_.colour));
    if (!rings.widths.empty()) {
        radialGrowth_ = RadialGrowth(rings.widths, params_.radialSpeed);
        // Years faster than Sb shorten thickening times by up to this ratio; the distance
        // bounds pass their years through the age warp, hence the 1/delta power.
        speedBound_ *= std::pow(radialGrowth_.maxSpeedRatio(), 1 / params_.age.delta);
    }
    plainThickening_ = params_.taper.nu == 0 && params_.direction.strength == 0 &&
                       sway_.radialJitter == 0 && params_.age.delta == 1 && radialGrowth_.empty();
}

GrowthSample GrowthField::evaluate(const Vec3& p) const {
    GrowthScratch scratch;
    GrowthSample out;
    evaluateBatch({&p, 1}, {&out, 1}, scratch);
    return out;
}

void GrowthField::evaluateBatch(std::span<const Vec3> input, std::span<GrowthSample> out,
                                GrowthScratch& scratch, size_t stencil) const {
    // One gather from the index for the whole batch; then, chunk by chunk (consecutive runs of
    // kChunk points, which callers keep spatially compact), exact pruning to what can matter
    // for that chunk, and the per-point work.
    const size_t n = input.size();
    if (n == 0) return;
    GrowthBuffers& buffers = scratch.buffers();
    const std::span<const Vec3> points =
        swayPoints(input, stencil, sway_, params_.wander, params_.warp, buffers.points);
    // Each chunk's box, once: the batch's and each group's are made of them.
    std::vector<PointBox>& chunkBoxes = buffers.chunkBoxes;
    chunkBoxes.resize((n + kChunk - 1) / kChunk);
    for (size_t c = 0; c < chunkBoxes.size(); ++c)
        chunkBoxes[c] = boxOf(points.subspan(c * kChunk, std::min(kChunk, n - c * kChunk)));
    const PointBox batch = boxOf(std::span<const PointBox>(chunkBoxes));
    const double maxTrunkTime = evaluateTrunk(points, batch, chunkBoxes, out, buffers.trunk);
    if (index_->branches().size() == 0) return;

    nearbyChains(batch, maxTrunkTime, buffers.candidateChains);
    const std::span<const uint32_t> chains = buffers.candidateChains;
    if (chains.empty()) return;
    for (size_t g0 = 0; g0 < n; g0 += kGroup) {
        const size_t g1 = std::min(n, g0 + kGroup);
        // The chains are culled again per group of chunks, whose trunk times vary less than
        // the batch's.
        std::span<const uint32_t> groupChains = chains;
        if (n > kGroup && chains.size() > kGroupCullAbove)
            groupChains =
                cullChains(chains,
                           boxOf(std::span<const PointBox>(chunkBoxes)
                                     .subspan(g0 / kChunk, (g1 - g0 + kChunk - 1) / kChunk)),
                           largest(std::span<const double>(buffers.trunk.chunkMaxima)
                                       .subspan(g0 / kChunk, (g1 - g0 + kChunk - 1) / kChunk)),
                           buffers.groupChains);
        for (size_t c0 = g0; c0 < g1; c0 += kChunk) {
            const size_t c1 = std::min(g1, c0 + kChunk);
            const std::span<const Vec3> chunkPoints = points.subspan(c0, c1 - c0);
            const std::span<GrowthSample> chunkOut = out.subspan(c0, c1 - c0);
            const PointBox& chunk = chunkBoxes[c0 / kChunk];
            buffers.quarters.reset(chunkPoints, chunk.lo, chunk.hi);
            prepareTileChains(groupChains, chunk, buffers.trunk.chunkMaxima[c0 / kChunk],
                              buffers.quarters, buffers.tileChains, buffers.cull);
            evaluateBranches(chunkPoints, buffers.quarters, buffers.tileChains, chunkOut,
                             buffers.branch);
        }
    }
}

}  // namespace nenrin
