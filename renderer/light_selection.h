#pragma once
/// Which lights a shading point samples by next-event estimation. With a few lights every one
/// gets a shadow ray at every vertex. With many local lights (points and rectangles) that costs
/// a ray per light per vertex, so one of them is picked instead, with a probability
/// proportional to an estimate of the light it sends to the point (its importance), and its
/// sample is divided by that probability. The sun and the sky are still sampled at every
/// vertex: they light everything from everywhere, so their share is large where a local
/// light's estimate knows nothing of it (in the sun's shadow it would still pick the sun).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "renderer/scene.h"

namespace nenrin {

class LightSelection {
public:
    /// `lights` must outlive this. Auto picks one local light past kEveryLocalLightUpTo of them.
    LightSelection(const std::vector<Light>& lights, LightSelectionMode mode);

    /// Under `auto`, scenes with at most this many point and rectangle lights sample them all.
    static constexpr size_t kEveryLocalLightUpTo = 2;

    /// The lights sampled at every vertex, in scene order: all of them, or with selection the
    /// distant lights and the environment.
    const std::vector<uint32_t>& everyVertex() const { return everyVertex_; }

    /// True if select() picks one local light at every vertex besides everyVertex().
    bool picksOne() const { return !local_.empty(); }

    /// Picks a local light for point p whose geometric normal n faces the outgoing direction,
    /// from a uniform u in [0, 1). Returns its index in the scene and sets `probability`;
    /// returns the light count if none can reach p (every importance 0). `cdf` is scratch.
    size_t select(const Vec3& p, const Vec3& n, double u, double& probability,
                  std::vector<double>& cdf) const;

    /// The probability with which light `index` is sampled at (p, n): 1 for everyVertex(),
    /// select()'s odds for a local light. Multiple importance sampling needs it when a
    /// BSDF-sampled ray finds a light.
    double probability(size_t index, const Vec3& p, const Vec3& n) const;

    /// The importance of `light` at (p, n): an estimate of the irradiance it gives there
    /// (luminance, W/m^2). Zero only where the light cannot light p at all: behind a one-sided
    /// rectangle, wholly below the surface's horizon, or black.
    static double importance(const Light& light, const Vec3& p, const Vec3& n);

private:
    /// A light select() picks from, with what a point light's importance needs packed in 40
    /// bytes: the scan over hundreds of them per vertex stays in the L1 cache.
    struct Local {
        Vec3 position;
        double luminance;
        uint32_t index;
        bool rect;  ///< importance from lights_[index]
    };
    double importanceOf(const Local& light, const Vec3& p, const Vec3& n) const;

    const std::vector<Light>& lights_;
    std::vector<uint32_t> everyVertex_;
    std::vector<Local> local_;  ///< empty: none picked
};

}  // namespace nenrin
