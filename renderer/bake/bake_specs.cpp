#include "renderer/bake/bake_specs.h"

#include <algorithm>
#include <cmath>

#include "util/input_error.h"

namespace nenrin {

SlicePlane parseSlicePlane(const std::string& name) {
    if (name == "cross") return SlicePlane::Cross;
    if (name == "radial") return SlicePlane::Radial;
    if (name == "tangential") return SlicePlane::Tangential;
    throw InputError("", "--plane", "expected cross, radial or tangential, found \"" + name + "\"");
}

const char* slicePlaneName(SlicePlane plane) {
    switch (plane) {
        case SlicePlane::Cross:
            return "cross";
        case SlicePlane::Radial:
            return "radial";
        case SlicePlane::Tangential:
            return "tangential";
    }
    return "?";
}

BakedGrid sliceGrid(const Skeleton& skeleton, const SliceSpec& spec) {
    BakedGrid g;
    g.width = spec.resX;
    g.height = spec.resY;
    g.depth = 1;
    if (spec.cut) {
        const PlaneCut& cut = *spec.cut;
        const double fx = g.width > 1 ? 1.0 / (g.width - 1) : 0;
        const double fy = g.height > 1 ? 1.0 / (g.height - 1) : 0;
        g.stepX = cut.right * fx;
        g.stepY = cut.up * -fy;
        g.origin = cut.origin + cut.up * (g.height > 1 ? 1.0 : 0.5) +
                   cut.right * (g.width > 1 ? 0.0 : 0.5);
        g.normal = cross(cut.right, cut.up);
        return g;
    }
    const double du = spec.width / spec.resX, dv = spec.height / spec.resY;
    if (spec.plane == SlicePlane::Cross) {
        Vec3 c = pithAtHeight(skeleton, spec.at);
        // Image x = tree +X, image up = tree +Y (seen from above).
        g.stepX = {du, 0, 0};
        g.stepY = {0, -dv, 0};
        g.origin = {c.x - 0.5 * spec.width + 0.5 * du, c.y + 0.5 * spec.height - 0.5 * dv, spec.at};
        g.normal = {0, 0, 1};
    } else {
        Vec3 c = pithAtHeight(skeleton, spec.bottom + 0.5 * spec.height);
        double top = spec.bottom + spec.height - 0.5 * dv;
        g.stepY = {0, 0, -dv};
        if (spec.plane == SlicePlane::Radial) {
            g.stepX = {du, 0, 0};
            g.origin = {c.x - 0.5 * spec.width + 0.5 * du, c.y + spec.at, top};
            g.normal = {0, -1, 0};
        } else {
            g.stepX = {0, du, 0};
            g.origin = {c.x + spec.at, c.y - 0.5 * spec.width + 0.5 * du, top};
            g.normal = {1, 0, 0};
        }
    }
    g.stepZ = {};
    return g;
}

BakedGrid volumeGrid(const VolumeSpec& spec) {
    BakedGrid g;
    Vec3 extent = spec.upper - spec.lower;
    double longest = std::max({extent.x, extent.y, extent.z});
    auto count = [&](double e) {
        return std::max(2, static_cast<int>(std::lround(spec.resolution * e / longest)));
    };
    g.width = count(extent.x);
    g.height = count(extent.y);
    g.depth = count(extent.z);
    g.origin = spec.lower;
    g.stepX = {extent.x / (g.width - 1), 0, 0};
    g.stepY = {0, extent.y / (g.height - 1), 0};
    g.stepZ = {0, 0, extent.z / (g.depth - 1)};
    return g;
}

}  // namespace nenrin
