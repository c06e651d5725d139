#include "skeleton/sources/kunii/a_system_tree.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "util/input_error.h"

namespace nenrin {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

struct Preset {
    const char* name;
    ASystemParams params;
};

// ABOP Fig. 2.7 (r1, r2, a1, a2); the divergence of ABOP's rule is /(180).
const Preset kPresets[] = {
    {"aono-kunii-a", {180, 0.9, 0.7, 5, 65, 0.707, 9}},
    {"aono-kunii-b", {180, 0.9, 0.7, 10, 60, 0.707, 9}},
    {"aono-kunii-c", {180, 0.9, 0.8, 20, 50, 0.707, 9}},
    {"aono-kunii-d", {180, 0.9, 0.8, 35, 35, 0.707, 9}},
    {"aono-kunii-spiral", {137.5, 0.9, 0.7, 10, 60, 0.707, 9}},
};

/// Rodrigues rotation of v about the unit axis k by `angle` radians.
Vec3 rotate(const Vec3& v, const Vec3& k, double angle) {
    double c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

class ASystemGrower {
public:
    ASystemGrower(const ASystemParams& p, double sway) : p_(p), sway_(sway) {}

    std::vector<ASystemAxis> grow() {
        int trunkForks = p_.trunkForks > 0 ? p_.trunkForks : p_.generations;
        growAxis(-1, -1, 0, Vec3{0, 0, 0}, Vec3{0, 0, 1}, Vec3{1, 0, 0}, 1.0, trunkForks);
        return std::move(axes_);
    }

private:
    /// One axis: `forks` internodes, each ending in a fork that sends out a lateral.
    void growAxis(int parent, int parentSegment, int order, Vec3 start, Vec3 dir, Vec3 normal,
                  double length, int forks) {
        int id = static_cast<int>(axes_.size());
        axes_.push_back({parent, parentSegment, order, {start}});
        double a1 = p_.branchAngle1 * kDegree * (order == 0 ? sway_ : 1.0);
        double a2 = p_.branchAngle2 * kDegree;
        struct Lateral {
            int segment;
            Vec3 start, dir, normal;
            double length;
            int forks;
        };
        std::vector<Lateral> laterals;
        Vec3 p = start;
        for (int k = 0; k < forks; ++k) {
            p = p + dir * length;
            axes_[static_cast<size_t>(id)].points.push_back(p);
            // The fork: lateral on one side of the branching plane, continuation on the other.
            Vec3 lateralDir = normalize(rotate(dir, normal, a2));
            Vec3 lateralNormal =
                normalize(rotate(normal, lateralDir, p_.divergenceAngle * kDegree));
            if (k + 1 < forks)
                laterals.push_back({k, p, lateralDir, lateralNormal, length * p_.contraction2,
                                    std::min(forks - k - 1, p_.generations - 1)});
            Vec3 next = normalize(rotate(dir, normal, -a1));
            normal = normalize(rotate(normal, next, p_.divergenceAngle * kDegree));
            // Keep the normal perpendicular to the axis against rounding drift.
            normal = normalize(normal - next * dot(normal, next));
            dir = next;
            length *= p_.contraction1;
        }
        for (const Lateral& l : laterals)
            growAxis(id, l.segment, order + 1, l.start, l.dir, l.normal, l.length, l.forks);
    }

    const ASystemParams& p_;
    double sway_;
    std::vector<ASystemAxis> axes_;
};

void require(bool ok, const std::string& parameter, const std::string& expected, double value) {
    if (!ok)
        throw InputError("A-system parameters", parameter,
                         fmt::format("is {}: expected {}", value, expected));
}

}  // namespace

ASystemParams aSystemPreset(const std::string& name) {
    for (const Preset& p : kPresets)
        if (name == p.name) return p.params;
    std::string names;
    for (const Preset& p : kPresets) names += std::string(names.empty() ? "" : ", ") + p.name;
    throw InputError("A-system parameters", "preset",
                     fmt::format("unknown preset \"{}\": expected one of {}", name, names));
}

std::vector<std::string> aSystemPresetNames() {
    std::vector<std::string> names;
    for (const Preset& p : kPresets) names.push_back(p.name);
    return names;
}

void validateASystemParams(const ASystemParams& p) {
    auto finite = [](double v) { return std::isfinite(v); };
    require(finite(p.divergenceAngle), "divergence_angle", "a finite angle (degrees)",
            p.divergenceAngle);
    require(finite(p.contraction1) && p.contraction1 > 0 && p.contraction1 <= 1, "contraction1",
            "a ratio in (0, 1]", p.contraction1);
    require(finite(p.contraction2) && p.contraction2 > 0 && p.contraction2 <= 1, "contraction2",
            "a ratio in (0, 1]", p.contraction2);
    require(finite(p.branchAngle1) && p.branchAngle1 >= 0 && p.branchAngle1 < 90, "branch_angle1",
            "an angle in [0, 90) degrees", p.branchAngle1);
    require(finite(p.branchAngle2) && p.branchAngle2 > 0 && p.branchAngle2 < 180, "branch_angle2",
            "an angle in (0, 180) degrees", p.branchAngle2);
    require(finite(p.widthRatio) && p.widthRatio > 0 && p.widthRatio <= 1, "width_ratio",
            "a ratio in (0, 1]", p.widthRatio);
    require(p.generations >= 1 && p.generations <= 14, "generations", "a count in 1..14",
            p.generations);
    require(p.trunkForks >= 0 && p.trunkForks <= 200, "trunk_forks",
            "a count in 0..200 (0 = generations)", p.trunkForks);
}

std::vector<ASystemAxis> growASystem(const ASystemParams& params, double trunkSway) {
    validateASystemParams(params);
    if (!(trunkSway >= 0 && trunkSway <= 1))
        throw InputError("A-system parameters", "trunk_sway",
                         fmt::format("is {}: expected a factor in [0, 1]", trunkSway));
    return ASystemGrower(params, trunkSway).grow();
}

Skeleton makeASystemTree(const ASystemParams& params, double height, double elongationSpeed,
                         double trunkSway) {
    if (!(height > 0) || !std::isfinite(height))
        throw InputError("A-system parameters", "height",
                         fmt::format("is {}: expected a height > 0 (m)", height));
    if (!(elongationSpeed > 0) || !std::isfinite(elongationSpeed))
        throw InputError("A-system parameters", "elongation_speed",
                         fmt::format("is {}: expected a speed > 0 (m/year)", elongationSpeed));
    std::vector<ASystemAxis> axes = growASystem(params, trunkSway);
    double scale = height / axes[0].points.back().z;
    Skeleton sk;
    std::vector<uint32_t> firstSegment(axes.size());
    std::vector<std::vector<double>> births(axes.size());
    for (size_t a = 0; a < axes.size(); ++a) {
        const ASystemAxis& axis = axes[a];
        std::vector<Vec3> pts;
        for (const Vec3& p : axis.points) pts.push_back(p * scale);
        double t0 = axis.parent < 0 ? 0.0
                                    : births[static_cast<size_t>(axis.parent)]
                                            [static_cast<size_t>(axis.parentSegment + 1)];
        std::vector<double>& t = births[a];
        t.push_back(t0);
        for (size_t i = 1; i < pts.size(); ++i)
            t.push_back(t.back() + length(pts[i] - pts[i - 1]) / elongationSpeed);
        // Widths: the trunk base is 1/50 of the height, each fork multiplies by widthRatio.
        std::vector<double> radii;
        double base = 0.01 * height * std::pow(params.widthRatio, axis.order);
        for (size_t i = 0; i < pts.size(); ++i)
            radii.push_back(base * std::pow(params.widthRatio, static_cast<double>(i) / 2));
        firstSegment[a] = static_cast<uint32_t>(sk.segments().size());
        if (axis.parent < 0) {
            sk.addTrunk(pts, t, radii);
        } else {
            ChainProperties props;
            props.gamma = std::pow(params.widthRatio, axis.order);
            props.diebackExponent = 1;
            sk.addBranch(firstSegment[static_cast<size_t>(axis.parent)] +
                             static_cast<uint32_t>(axis.parentSegment),
                         pts, t, props, radii);
        }
    }
    return sk;
}

}  // namespace nenrin
