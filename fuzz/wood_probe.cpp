#include "fuzz/wood_probe.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fuzz/fuzz_input.h"
#include "grain/growth_field.h"
#include "shader/wood_shader.h"
#include "skeleton/skeleton_index.h"

namespace nenrin::fuzz {

namespace {

bool finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check(bool ok, const char* what, const Vec3& p) {
    if (!ok)
        fail(std::string("non-finite ") + what + " at (" + std::to_string(p.x) + ", " +
             std::to_string(p.y) + ", " + std::to_string(p.z) + ")");
}

}  // namespace

Skeleton probeTree() {
    Skeleton s;
    s.addTrunk({{0, 0, 0}, {0, 0, 2}, {0, 0, 4}, {0, 0, 6}}, {0, 4, 8, 12});
    ChainProperties props;
    s.addBranch(1, {{0, 0, 2}, {0.8, 0, 2.5}, {1.5, 0.1, 3}}, {4, 6, 8}, props);
    s.addBranch(2, {{0, 0, 4}, {-0.7, 0.3, 4.6}}, {8, 10}, props);
    return s;
}

void probeWood(const Skeleton& skeleton, const GrainParams& params) {
    if (skeleton.segments().empty()) return;
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const SkeletonNode& n : skeleton.nodes()) {
        lo = {std::min(lo.x, n.position.x), std::min(lo.y, n.position.y),
              std::min(lo.z, n.position.z)};
        hi = {std::max(hi.x, n.position.x), std::max(hi.y, n.position.y),
              std::max(hi.z, n.position.z)};
    }
    Vec3 margin = (hi - lo) * 0.1 + Vec3{0.05, 0.05, 0.05};
    lo = lo - margin;
    hi = hi + margin;

    std::vector<Vec3> points;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k)
                points.push_back({lo.x + (hi.x - lo.x) * i / 3, lo.y + (hi.y - lo.y) * j / 3,
                                  lo.z + (hi.z - lo.z) * k / 3});
    size_t nodes = std::min<size_t>(skeleton.nodes().size(), 32);
    for (size_t i = 0; i < nodes; ++i)
        points.push_back(skeleton.nodes()[i].position + Vec3{0.003, -0.002, 0.001});
    points.push_back({1e4, -1e4, 1e4});  // as far as a bake may ask (kMaxCoordinate)

    SkeletonIndex index(skeleton);
    GrowthField field(index, params);
    WoodShader shader(field);
    std::vector<WoodSurfaceSample> out(points.size());
    WoodScratch scratch;
    shader.evaluateSurface(points, {}, out, scratch);
    for (size_t i = 0; i < points.size(); ++i) {
        const WoodSurfaceSample& s = out[i];
        check(std::isfinite(s.T), "growth time", points[i]);
        check(std::isfinite(s.albedo.r) && std::isfinite(s.albedo.g) && std::isfinite(s.albedo.b),
              "albedo", points[i]);
        check(std::isfinite(s.knot) && std::isfinite(s.lateWood), "knot or late wood", points[i]);
        check(finite(s.fibre) && finite(s.gradientT) && finite(s.reliefGradient),
              "fibre, gradient or relief", points[i]);
    }
}

}  // namespace nenrin::fuzz
