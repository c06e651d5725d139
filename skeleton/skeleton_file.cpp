#include "skeleton/skeleton_file.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>

#include "skeleton/ring_series.h"
#include "skeleton/segment_geometry.h"
#include "util/json_reader.h"
#include "util/limits.h"

namespace nenrin {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
/// How far a branch's given start point may lie from its parent chain.
constexpr double kOnChainTolerance = 1e-3;
/// m: no tree lays down a ring wider than this in a year.
constexpr double kMaxRingWidth = 0.1;
/// Past this eq. 10's dieback is a wall already: larger exponents only overflow.
constexpr double kMaxDiebackExponent = 100;

struct ChainGeometry {
    std::vector<Vec3> points;
    std::vector<double> births;
    uint32_t firstSegment;
};

struct BranchDefaults {
    double gamma = 0.5;
    double deathTime = kNeverDies;
    double diebackExponent = 1.0;
    double length = 0;  // 0: "as long as the trunk"
};

/// Where along a chain a branch starts: the segment and the point on it.
struct Attachment {
    uint32_t segment;  // global segment id
    Vec3 point;
    double birth;
};

double polylineLength(const std::vector<Vec3>& pts) {
    double l = 0;
    for (size_t i = 1; i < pts.size(); ++i) l += length(pts[i] - pts[i - 1]);
    return l;
}

Attachment attachAtDistance(const ChainGeometry& c, double at) {
    double walked = 0;
    for (size_t i = 0; i + 1 < c.points.size(); ++i) {
        double l = length(c.points[i + 1] - c.points[i]);
        if (at <= walked + l || i + 2 == c.points.size()) {
            double t = l > 0 ? std::clamp((at - walked) / l, 0.0, 1.0) : 0;
            return {static_cast<uint32_t>(c.firstSegment + i),
                    lerp(c.points[i], c.points[i + 1], t),
                    c.births[i] + (c.births[i + 1] - c.births[i]) * t};
        }
        walked += l;
    }
    return {c.firstSegment, c.points[0], c.births[0]};
}

class SkeletonParser {
public:
    explicit SkeletonParser(const std::string& file) : file_(file) {}

    Skeleton parse(const nlohmann::json& json) {
        JsonReader root(json, file_);
        root.string("description", "");
        root.choice("format", "nenrin-skeleton", {"nenrin-skeleton"});
        elongationSpeed_ = root.atLeast("elongation_speed", 1.0, kMinElongationSpeed,
                                        "m/year: 0.1 mm a year, slower than any tree grows");

        if (!root.has("trunk")) throw root.error("trunk", "missing required trunk");
        auto trunk = root.object("trunk");
        std::vector<Vec3> points = trunk->requireVec3List("points");
        if (points.size() < 2)
            throw trunk->error(
                "points", fmt::format("expected at least 2 trunk points, found {}", points.size()));
        checkSegments(points, *trunk, "points");
        std::vector<double> births = trunk->has("birth_times")
                                         ? explicitBirthTimes(*trunk, points.size(), std::nullopt)
                                         : birthTimes(points, 0.0);
        std::vector<double> radii = readRadii(*trunk, points.size());
        trunk->finish();
        ChainGeometry trunkGeometry{points, births, 0};
        skeleton_.addTrunk(trunkGeometry.points, trunkGeometry.births, radii);
        trunkLength_ = polylineLength(points);

        if (auto d = root.object("branch_defaults")) {
            defaults_ = readProperties(*d, defaults_);
            d->finish();
        }
        for (auto& b : root.objectList("branches")) parseBranch(b, trunkGeometry, true);
        if (root.has("ring_widths") && root.has("ring_series"))
            throw root.error("ring_series", "expected ring_widths or ring_series, not both");
        if (root.has("ring_widths")) {
            std::vector<double> widths = root.numberList("ring_widths");
            bool anyRing = false;
            for (size_t i = 0; i < widths.size(); ++i) {
                // 0 is a locally absent ring: it merges with its neighbour.
                if (!(widths[i] == 0 || widths[i] >= kMinRingWidth) || !std::isfinite(widths[i]) ||
                    widths[i] > kMaxRingWidth)
                    throw root.error("ring_widths",
                                     fmt::format("entry {} is {:g}: expected a ring width in m, "
                                                 "0 (an absent ring) or from {:g} (1 um) to {:g}",
                                                 i, widths[i], kMinRingWidth, kMaxRingWidth));
                anyRing |= widths[i] > 0;
            }
            if (!widths.empty() && !anyRing)
                throw root.error("ring_widths", "every ring is 0: expected some growth");
            skeleton_.setRingWidths(std::move(widths));
        }
        if (root.has("latewood_shares")) {
            std::vector<double> shares = root.numberList("latewood_shares");
            for (size_t i = 0; i < shares.size(); ++i)
                if (!(shares[i] >= 0.01 && shares[i] <= 0.99))
                    throw root.error("latewood_shares",
                                     fmt::format("entry {} is {}: expected a share of the ring "
                                                 "from 0.01 to 0.99",
                                                 i, shares[i]));
            skeleton_.setLatewoodShares(std::move(shares));
        }
        if (auto series = root.object("ring_series")) {
            // A measured series from a Tucson .rwl file, relative to this skeleton file.
            std::string name = series->string("file", "");
            if (name.empty()) throw series->error("file", "expected the .rwl file's name");
            std::string id = series->string("series", "");
            if (id.empty()) throw series->error("series", "expected a series ID of that file");
            double meanMm = series->zeroOrAtLeast("mean_width", 0, 1000 * kMinRingWidth,
                                                  "mm: 1 um; 0 keeps the measured widths");
            if (meanMm > 1000 * kMaxRingWidth)
                throw series->error("mean_width",
                                    fmt::format("expected at most {:g} mm, found {:g}",
                                                1000 * kMaxRingWidth, meanMm));
            series->finish();
            std::filesystem::path p(name);
            if (p.is_relative()) p = std::filesystem::path(file_).parent_path() / p;
            RingSeriesFile rwl = readTucsonRwl(p.string());
            skeleton_.setRingWidths(ringWidthsMetres(rwl.find(id), meanMm, rwl.path));
        }
        root.object("source");  // provenance, free-form: read by people, not by nenrin
        root.finish();
        return std::move(skeleton_);
    }

private:
    std::vector<double> birthTimes(const std::vector<Vec3>& pts, double start) const {
        std::vector<double> t{start};
        for (size_t i = 1; i < pts.size(); ++i)
            t.push_back(t.back() + length(pts[i] - pts[i - 1]) / elongationSpeed_);
        return t;
    }

    /// Explicit per-point birth times (key "birth_times"): finite, >= 0, never decreasing along
    /// the chain, and not before `start` (the branch's birth on its parent) when given.
    std::vector<double> explicitBirthTimes(JsonReader& r, size_t count,
                                           std::optional<double> start) {
        std::vector<double> t = r.numberList("birth_times");
        if (t.size() != count)
            throw r.error("birth_times", fmt::format("expected {} birth times (one per point), "
                                                     "found {}",
                                                     count, t.size()));
        double previous = start.value_or(0.0);
        for (size_t i = 0; i < t.size(); ++i) {
            if (!std::isfinite(t[i]) || t[i] < 0)
                throw r.error("birth_times",
                              fmt::format("entry {} is {}: expected years >= 0", i, t[i]));
            if (t[i] < previous - 1e-9)
                throw r.error("birth_times",
                              fmt::format("entry {} ({}) is earlier than {} before it: expected "
                                          "birth times that never decrease from the base",
                                          i, t[i], previous));
            previous = t[i];
        }
        return t;
    }

    /// Optional per-point radii (key "radii", m, >= 0); empty when not given.
    std::vector<double> readRadii(JsonReader& r, size_t count) {
        if (!r.has("radii")) return {};
        std::vector<double> radii = r.numberList("radii");
        if (radii.size() != count)
            throw r.error("radii", fmt::format("expected {} radii (one per point), found {}", count,
                                               radii.size()));
        for (size_t i = 0; i < radii.size(); ++i)
            if (!std::isfinite(radii[i]) || radii[i] < 0)
                throw r.error("radii", fmt::format("entry {} is {}: expected a radius >= 0 (m)", i,
                                                   radii[i]));
        return radii;
    }

    /// `pts[0]` is the branch start (not written by the user) when `startPrepended`: messages
    /// count the user's points from 0.
    void checkSegments(const std::vector<Vec3>& pts, const JsonReader& r, const std::string& key,
                       bool startPrepended = false) {
        for (size_t i = 1; i < pts.size(); ++i) {
            if (length(pts[i] - pts[i - 1]) >= 1e-9) continue;
            if (startPrepended && i == 1)
                throw r.error(key,
                              "point 0 coincides with the branch's start on its parent: "
                              "expected segments of non-zero length");
            size_t a = startPrepended ? i - 2 : i - 1, b = startPrepended ? i - 1 : i;
            throw r.error(key, fmt::format("points {} and {} coincide: expected segments of "
                                           "non-zero length",
                                           a, b));
        }
    }

    BranchDefaults readProperties(JsonReader& r, const BranchDefaults& base) {
        BranchDefaults p = base;
        p.gamma = r.atLeast("gamma", base.gamma, kMinBranchGamma,
                            "of the trunk's radial speed: a branch thickening a thousandth as "
                            "fast");
        p.deathTime = r.has("death_time") ? r.atLeast("death_time", 1, kMinDeathTime, "years")
                                          : base.deathTime;
        p.diebackExponent =
            r.inRange("dieback_exponent", base.diebackExponent, 0, kMaxDiebackExponent);
        p.length =
            r.has("length") ? r.atLeast("length", 1, kMinBranchLength, "m: 1 mm") : base.length;
        return p;
    }

    Attachment findStart(JsonReader& b, const ChainGeometry& parent, bool onTrunk) {
        if (b.has("on_segment") && !b.has("start"))
            throw b.error("on_segment", "\"on_segment\" goes with \"start\"");
        int given = b.has("height") + b.has("start") + b.has("at");
        if (given != 1)
            throw b.error("",
                          "expected exactly one of \"height\" (m, on the trunk), \"at\" (m "
                          "along the parent chain) or \"start\" ([x, y, z] on the parent)");
        if (b.has("height")) {
            if (!onTrunk)
                throw b.error("height",
                              "\"height\" places branches on the trunk; use \"at\" "
                              "(distance along the parent branch) for sub-branches");
            double h = b.requireNumber("height");
            for (size_t i = 0; i + 1 < parent.points.size(); ++i) {
                double z0 = parent.points[i].z, z1 = parent.points[i + 1].z;
                if ((h - z0) * (h - z1) <= 0 && z0 != z1) {
                    double t = (h - z0) / (z1 - z0);
                    return {static_cast<uint32_t>(parent.firstSegment + i),
                            lerp(parent.points[i], parent.points[i + 1], t),
                            parent.births[i] + (parent.births[i + 1] - parent.births[i]) * t};
                }
            }
            throw b.error("height",
                          fmt::format("height {} m is off the trunk: expected a height between "
                                      "the trunk's lowest and highest point",
                                      h));
        }
        if (b.has("at")) {
            double at = b.nonNegative("at", 0);
            double len = polylineLength(parent.points);
            if (at > len)
                throw b.error("at", fmt::format("{} m is past the end of the parent chain "
                                                "({:.4g} m long)",
                                                at, len));
            return attachAtDistance(parent, at);
        }
        Vec3 s = b.requireVec3("start");
        double best = std::numeric_limits<double>::infinity();
        Attachment att{};
        size_t first = 0, last = parent.points.size() - 1;
        if (b.has("on_segment")) {  // a start on a joint: which of the two segments
            first = static_cast<size_t>(
                b.integer("on_segment", 0, 0, static_cast<long long>(last) - 1));
            last = first + 1;
        }
        for (size_t i = first; i + 1 <= last; ++i) {
            auto pr = projectOntoSegment(s, parent.points[i], parent.points[i + 1]);
            if (pr.distance2 < best) {
                best = pr.distance2;
                att = {static_cast<uint32_t>(parent.firstSegment + i), s,
                       parent.births[i] + (parent.births[i + 1] - parent.births[i]) * pr.t};
            }
        }
        if (std::sqrt(best) > kOnChainTolerance)
            throw b.error("start", fmt::format("the branch starts {:.4g} m off its parent {}: "
                                               "expected a point on it (within {} m)",
                                               std::sqrt(best), onTrunk ? "trunk" : "branch",
                                               kOnChainTolerance));
        return att;
    }

    Vec3 readDirection(JsonReader& b) {
        bool angles = b.has("azimuth") || b.has("elevation");
        if (b.has("direction") && angles)
            throw b.error("direction",
                          "give either \"direction\" or \"azimuth\"/\"elevation\", "
                          "not both");
        if (b.has("direction")) {
            Vec3 d = b.requireVec3("direction");
            if (length(d) < 1e-12) throw b.error("direction", "expected a non-zero vector");
            return normalize(d);
        }
        if (!angles)
            throw b.error("",
                          "missing direction: expected \"direction\" [x, y, z], "
                          "\"azimuth\"/\"elevation\" (degrees) or \"points\"");
        double az = b.number("azimuth", 0) * kDegree;
        double el = b.inRange("elevation", 0, -90, 90) * kDegree;
        return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
    }

    void parseBranch(JsonReader& b, const ChainGeometry& parent, bool onTrunk) {
        Attachment att = findStart(b, parent, onTrunk);
        if (b.has("start_birth_time")) {
            double t = b.nonNegative("start_birth_time", 0);
            if (t < att.birth - 1e-9)
                throw b.error("start_birth_time",
                              fmt::format("{} years is before the parent reached this point ({} "
                                          "years): a branch cannot start before its parent",
                                          t, att.birth));
            att.birth = t;
        }
        BranchDefaults props = readProperties(b, defaults_);
        std::vector<Vec3> points{att.point};
        std::vector<double> births, radii;
        if (b.has("points")) {
            if (b.has("direction") || b.has("azimuth") || b.has("elevation") || b.has("length"))
                throw b.error("points",
                              "a branch is given either by \"points\" or by a "
                              "direction and length, not both");
            for (const Vec3& p : b.requireVec3List("points")) points.push_back(p);
            if (points.size() < 2) throw b.error("points", "expected at least one point");
            checkSegments(points, b, "points", true);
            if (b.has("birth_times")) {
                births = explicitBirthTimes(b, points.size() - 1, att.birth);
                births.insert(births.begin(), att.birth);
            }
            radii = readRadii(b, points.size() - 1);
        } else {
            for (const char* key : {"birth_times", "radii"})
                if (b.has(key))
                    throw b.error(key, "per-point values need a polyline branch (\"points\")");
            Vec3 d = readDirection(b);
            double len = props.length > 0 ? props.length : trunkLength_;
            points.push_back(att.point + d * len);
        }
        if (!radii.empty())
            radii.insert(radii.begin(),
                         b.has("start_radius") ? b.nonNegative("start_radius", 0) : radii[0]);
        else if (b.has("start_radius"))
            throw b.error("start_radius", "a start radius needs \"radii\" for the points too");
        if (births.empty()) births = birthTimes(points, att.birth);
        ChainGeometry geometry{points, births, static_cast<uint32_t>(skeleton_.segments().size())};
        skeleton_.addBranch(att.segment, geometry.points, geometry.births,
                            {props.gamma, props.deathTime, props.diebackExponent}, radii);
        for (auto& sub : b.objectList("branches")) parseBranch(sub, geometry, false);
        b.finish();
    }

    std::string file_;
    Skeleton skeleton_;
    double elongationSpeed_ = 1;
    double trunkLength_ = 0;
    BranchDefaults defaults_;
};

}  // namespace

Skeleton parseSkeleton(const nlohmann::json& json, const std::string& file) {
    return SkeletonParser(file).parse(json);
}

Skeleton loadSkeletonFile(const std::string& path) {
    return parseSkeleton(parseJsonFile(path), path);
}

}  // namespace nenrin
