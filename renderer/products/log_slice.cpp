#include "renderer/products/log_slice.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "renderer/products/cut_plan.h"
#include "util/hash.h"

namespace nenrin {

TriangleMesh logSliceMesh(const GrowthField& field, const LogSliceParams& params) {
    CutPlanParams plan;
    plan.maxRadius = params.maxRadius;
    const int n = params.segments;
    const double half = 0.5 * params.thickness;
    std::vector<double> radius(n);
    for (int i = 0; i < n; ++i) {
        // The outline is the smaller of the two faces' radii, so no face shows air.
        double theta = 2 * std::numbers::pi * i / n;
        double r = std::min(logRadius(field, plan, params.height - half, theta),
                            logRadius(field, plan, params.height + half, theta));
        radius[i] = r + params.bark;
    }
    // Drying checks: each a V notch in the outline at a seeded azimuth, its walls the wood
    // inside (the disc is a fan about the pith, so a radial notch keeps it star-shaped).
    SplitMix rng(hashCombine(params.checkSeed, 0xc4ec5ull));
    for (int c = 0; c < params.checks; ++c) {
        const double centre =
            2 * std::numbers::pi * (c + 0.3 + 0.4 * rng.uniform()) / std::max(1, params.checks);
        const double depth = params.checkDepth * (0.6 + 0.8 * rng.uniform());
        for (int i = 0; i < n; ++i) {
            double theta = 2 * std::numbers::pi * i / n;
            double d = std::remainder(theta - centre, 2 * std::numbers::pi);
            // Half-opening angle at the bark, at least one and a half outline steps.
            double halfAngle =
                std::max(0.5 * params.checkWidth / radius[i], 1.5 * 2 * std::numbers::pi / n);
            double v = 1 - std::abs(d) / halfAngle;
            if (v > 0) radius[i] *= 1 - depth * v;
        }
    }
    // Object x = tree x, object z = -tree y (see logSliceTreeFromObject).
    auto rim = [&](int i, double y) {
        double theta = 2 * std::numbers::pi * i / n;
        return Vec3{radius[i] * std::cos(theta), y, -radius[i] * std::sin(theta)};
    };
    TriangleMesh m;
    m.positions.push_back({0, half, 0});
    m.positions.push_back({0, -half, 0});
    for (int i = 0; i < n; ++i) {
        m.positions.push_back(rim(i, half));
        m.positions.push_back(rim(i, -half));
    }
    auto top = [](int i) { return uint32_t(2 + 2 * i); };
    auto bottom = [](int i) { return uint32_t(3 + 2 * i); };
    for (int i = 0; i < n; ++i) {
        int j = (i + 1) % n;
        // Counter-clockwise seen from outside: +y for the top, -y for the bottom.
        m.triangles.push_back({0, top(i), top(j)});
        m.triangles.push_back({1, bottom(j), bottom(i)});
        m.triangles.push_back({top(i), bottom(i), bottom(j)});
        m.triangles.push_back({top(i), bottom(j), top(j)});
    }
    return m;
}

RigidTransform logSliceTreeFromObject(const GrowthField& field, const LogSliceParams& params) {
    return RigidTransform::fromAxes({1, 0, 0}, {0, 0, 1}, {0, -1, 0},
                                    pithAtHeight(field.skeleton(), params.height));
}

}  // namespace nenrin
