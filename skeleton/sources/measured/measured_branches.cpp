#include "skeleton/sources/measured/measured_branches.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {

namespace {

constexpr double kDegree = std::numbers::pi / 180;
/// Gamma derived from diameters is kept in this range (a measurement slip, or a branch much
/// younger than its diameter suggests, should not make a branch outgrow the trunk tenfold).
constexpr double kMinDerivedGamma = 0.05, kMaxDerivedGamma = 2.0;

struct Internode {
    double length, azimuth, elevation, diameter;  // m, rad, rad, m
};

/// One branch number: "B120" -> digits {1, 2, 0}, order 2, parent "B100".
struct BranchNumber {
    std::string key;
    std::vector<int> digits;
    int order = 0;
    std::string parentKey() const {  // "" for first-order branches (parent = trunk)
        if (order == 1) return "";
        std::string p = key;
        p[static_cast<size_t>(order)] = '0';
        return p;
    }
};

BranchNumber parseBranchNumber(const std::string& key, const std::string& file,
                               const std::string& where) {
    auto bad = [&](const std::string& why) {
        return InputError(file, where,
                          fmt::format("bad branch number \"{}\": {} (expected B and digits, the "
                                      "non-zero ones first: B100, B120, B121)",
                                      key, why));
    };
    if (key.size() < 2 || key[0] != 'B') throw bad("it must start with B");
    BranchNumber n{key, {}, 0};
    bool zeroSeen = false;
    for (size_t i = 1; i < key.size(); ++i) {
        char c = key[i];
        if (c < '0' || c > '9') throw bad(fmt::format("'{}' is not a digit", c));
        int d = c - '0';
        if (d == 0) zeroSeen = true;
        if (d != 0 && zeroSeen) throw bad("a non-zero digit after a 0");
        if (d != 0) n.order += 1;
        n.digits.push_back(d);
    }
    if (n.order == 0) throw bad("B0... names no branch");
    return n;
}

std::vector<Internode> readInternodes(const nlohmann::json& v, const std::string& file,
                                      const std::string& where, double unit) {
    if (!v.is_array() || v.empty())
        throw InputError(file, where,
                         fmt::format("expected a non-empty array of internodes [l, theta, phi, d], "
                                     "found {}",
                                     v.is_array() ? "an empty array" : jsonTypeName(v)));
    std::vector<Internode> out;
    for (size_t i = 0; i < v.size(); ++i) {
        std::string at = fmt::format("{}[{}]", where, i);
        const auto& e = v[i];
        if (!e.is_array() || e.size() != 4)
            throw InputError(
                file, at,
                fmt::format("expected an internode [l, theta, phi, d] (length, azimuth deg, "
                            "elevation deg, base diameter), found {}",
                            e.is_array() ? fmt::format("{} elements", e.size()) : jsonTypeName(e)));
        double x[4];
        for (int k = 0; k < 4; ++k) {
            std::string ak = fmt::format("{}[{}]", at, k);
            if (!e[k].is_number())
                throw InputError(file, ak,
                                 fmt::format("expected a number, found {}", jsonTypeName(e[k])));
            x[k] = e[k].get<double>();
            if (!std::isfinite(x[k])) throw InputError(file, ak, "expected a finite number");
        }
        // Bounds of a tree (the tallest are ~115 m, the thickest ~10 m across).
        if (!(x[0] * unit >= 1e-6 && x[0] * unit <= 100))
            throw InputError(file, at + "[0]",
                             fmt::format("internode length l must be in [1e-6, 100] m, found {:g} "
                                         "(the file's unit is {:g} m)",
                                         x[0], unit));
        if (!(std::abs(x[1]) <= 3600))
            throw InputError(
                file, at + "[1]",
                fmt::format("azimuth theta must be in [-3600, 3600] degrees, found {:g}", x[1]));
        if (!(x[2] >= -90 && x[2] <= 90))
            throw InputError(
                file, at + "[2]",
                fmt::format("elevation phi must be in [-90, 90] degrees, found {}", x[2]));
        if (!(x[3] > 0 && x[3] * unit <= 20))
            throw InputError(file, at + "[3]",
                             fmt::format("base diameter d must be in (0, 20] m, found {:g} (the "
                                         "file's unit is {:g} m)",
                                         x[3], unit));
        out.push_back({x[0] * unit, x[1] * kDegree, x[2] * kDegree, x[3] * unit});
    }
    return out;
}

/// The paper's offset of one internode (section 4.2 (1)): azimuth theta from +Y towards +X.
Vec3 offset(const Internode& n) {
    return {n.length * std::sin(n.azimuth) * std::cos(n.elevation),
            n.length * std::cos(n.azimuth) * std::cos(n.elevation),
            n.length * std::sin(n.elevation)};
}

struct BranchSpec {
    BranchNumber number;
    std::string where;  // JSON path of the branch object
    long long node = 0;
    std::vector<Internode> internodes;
    double startTime = -1;  // < 0: the parent's time at the node
    double deathTime = kNeverDies;
    double gamma = 0;  // 0: from the diameters
};

/// The branch objects keyed by number, in file order.
std::vector<BranchSpec> readBranchSpecs(const nlohmann::json& branchesJson, const std::string& file,
                                        double unit) {
    std::vector<BranchSpec> specs;
    size_t width = 0;
    std::string widthKey;
    for (auto it = branchesJson.begin(); it != branchesJson.end(); ++it) {
        BranchSpec s;
        s.where = "branches." + it.key();
        s.number = parseBranchNumber(it.key(), file, s.where);
        if (width == 0) {
            width = it.key().size();
            widthKey = it.key();
        } else if (it.key().size() != width) {
            throw InputError(file, s.where,
                             fmt::format("branch numbers must all have the same number of digits "
                                         "(\"{}\" has {}, \"{}\" has {})",
                                         widthKey, width - 1, it.key(), it.key().size() - 1));
        }
        if (!it.value().is_object())
            throw InputError(file, s.where,
                             fmt::format("expected an object, found {}", jsonTypeName(it.value())));
        nlohmann::json rest = it.value();
        if (!rest.contains("internodes"))
            throw InputError(file, s.where + ".internodes", "missing required internode list");
        s.internodes = readInternodes(rest["internodes"], file, s.where + ".internodes", unit);
        rest.erase("internodes");
        JsonReader b(rest, file, s.where);
        if (!b.has("node"))
            throw b.error("node", "missing: the parent's node the branch leaves from");
        s.node = b.integer("node", 0, 0, 1000000);
        if (b.has("start_time")) s.startTime = b.nonNegative("start_time", 0);
        if (b.has("death_time")) s.deathTime = b.requirePositive("death_time");
        if (b.has("gamma")) s.gamma = b.requirePositive("gamma");
        b.finish();
        specs.push_back(std::move(s));
    }
    return specs;
}

double pathLength(const std::vector<Internode>& v) {
    double s = 0;
    for (const auto& n : v) s += n.length;
    return s;
}

/// A built chain: its nodes (positions, times, radii) and first segment.
struct BuiltChain {
    uint32_t chain = 0, firstSegment = 0;
    std::vector<Vec3> points;
    std::vector<double> times, radii;
    double deathTime = kNeverDies;
};

BuiltChain layOut(const Vec3& start, double startTime, const std::vector<Internode>& internodes,
                  double speed) {
    BuiltChain c;
    c.points.push_back(start);
    c.times.push_back(startTime);
    for (const auto& n : internodes) {
        c.points.push_back(c.points.back() + offset(n));
        c.times.push_back(c.times.back() + n.length / speed);
        c.radii.push_back(0.5 * n.diameter);
    }
    // Cones between nodes; the tip tapers to half the last internode's base radius.
    c.radii.push_back(0.25 * internodes.back().diameter);
    return c;
}

/// The top level: "trunk" and "branches" as they are, and the keys beside them.
struct TopLevel {
    nlohmann::json trunk, branches;
    double unit = 1;          ///< m per unit of the file's lengths and diameters
    double age = 0;           ///< years; 0 when the file gives the elongation speed instead
    double speed = 0;         ///< m/year; 0 when the file gives the age instead
    double defaultGamma = 0;  ///< 0: from the diameters
};

TopLevel readTopLevel(const nlohmann::json& json, const std::string& file) {
    // "trunk" and the internode lists are arrays of arrays, read here by hand; everything else
    // goes through JsonReader (a copy without them, so finish() still catches unknown keys).
    nlohmann::json top = json;
    if (!top.is_object())
        throw InputError(file, "(top level)",
                         fmt::format("expected an object, found {}", jsonTypeName(top)));
    TopLevel t;
    t.trunk = top.contains("trunk") ? top["trunk"] : nlohmann::json();
    t.branches = top.contains("branches") ? top["branches"] : nlohmann::json::object();
    top.erase("trunk");
    top.erase("branches");
    JsonReader r(top, file);
    r.string("description", "");
    r.choice("format", "nenrin-measured-branches", {"nenrin-measured-branches"});
    t.unit = r.choice("unit", "m", {"m", "cm"}) == "cm" ? 0.01 : 1.0;
    if (r.has("age") == r.has("elongation_speed"))
        throw r.error("",
                      "give exactly one of \"age\" (years at measurement) and "
                      "\"elongation_speed\" (m/year): they define the birth times");
    t.age = r.has("age") ? r.requirePositive("age") : 0;
    t.speed = r.has("elongation_speed") ? r.requirePositive("elongation_speed") : 0;
    t.defaultGamma = r.has("gamma") ? r.requirePositive("gamma") : 0;
    r.finish();
    return t;
}

/// The branches, keyed by their numbers, sorted parents before children: by order, then by
/// number.
std::vector<BranchSpec> readBranches(const nlohmann::json& branchesJson, const std::string& file,
                                     double unit) {
    if (!branchesJson.is_object())
        throw InputError(
            file, "branches",
            fmt::format("expected an object keyed by branch number (\"B100\": {{...}}), "
                        "found {}",
                        jsonTypeName(branchesJson)));
    std::vector<BranchSpec> specs = readBranchSpecs(branchesJson, file, unit);
    std::sort(specs.begin(), specs.end(), [](const BranchSpec& a, const BranchSpec& b) {
        return a.number.order != b.number.order ? a.number.order < b.number.order
                                                : a.number.key < b.number.key;
    });
    return specs;
}

/// The path length from the ground to the farthest tip, checking that every branch's parent
/// exists and has the node the branch leaves from.
double farthestTipPath(const std::vector<Internode>& trunk, const std::vector<BranchSpec>& specs,
                       const std::string& file) {
    std::map<std::string, double> pathTo;  // path length from the ground to a chain's start
    std::map<std::string, const BranchSpec*> byKey;
    double longest = pathLength(trunk);
    for (const auto& s : specs) {
        std::string parent = s.number.parentKey();
        const std::vector<Internode>* parentNodes = &trunk;
        double parentPath = 0;
        if (!parent.empty()) {
            auto found = byKey.find(parent);
            if (found == byKey.end())
                throw InputError(file, s.where,
                                 fmt::format("parent branch {} is missing (a branch {} hangs on "
                                             "the branch with its last non-zero digit set to 0)",
                                             parent, s.number.key));
            parentNodes = &found->second->internodes;
            parentPath = pathTo.at(parent);
        }
        if (s.node > static_cast<long long>(parentNodes->size()))
            throw InputError(
                file, s.where + ".node",
                fmt::format("node {} is past the tip of {} ({} internodes: nodes 0..{})", s.node,
                            parent.empty() ? std::string("the trunk") : parent, parentNodes->size(),
                            parentNodes->size()));
        double p = parentPath;
        for (long long i = 0; i < s.node; ++i) p += (*parentNodes)[static_cast<size_t>(i)].length;
        pathTo[s.number.key] = p;
        longest = std::max(longest, p + pathLength(s.internodes));
        byKey[s.number.key] = &s;
    }
    return longest;
}

/// Branch `s` laid out from its parent's node: it starts when the parent reached the node (or
/// at its start_time, not before) and dies with its parent at the latest.
BuiltChain layOutBranch(const BranchSpec& s, const BuiltChain& parent, double speed,
                        const std::string& file) {
    size_t node = static_cast<size_t>(s.node);
    double parentTime = parent.times[node];
    double start = parentTime;
    if (s.startTime >= 0) {
        if (s.startTime < parentTime - 1e-9)
            throw InputError(file, s.where + ".start_time",
                             fmt::format("the branch starts at {} years, before its parent "
                                         "reached node {} ({} years)",
                                         s.startTime, node, parentTime));
        start = std::max(s.startTime, parentTime);
    }
    BuiltChain c = layOut(parent.points[node], start, s.internodes, speed);
    if (s.deathTime <= start)
        throw InputError(file, s.where + ".death_time",
                         fmt::format("the branch dies at {} years, before it starts ({} years)",
                                     s.deathTime, start));
    if (parent.deathTime <= start)
        throw InputError(file, s.where,
                         fmt::format("its parent {} is dead at {} years, before the branch "
                                     "starts ({} years)",
                                     s.number.parentKey(), parent.deathTime, start));
    // A branch dies with its parent at the latest.
    c.deathTime = std::min(s.deathTime, parent.deathTime);
    return c;
}

/// Adds branch `s` (laid out in `c`) to the skeleton on its parent's segment at its node.
/// Gamma where not given comes from the diameters: the branch's mean radial speed (base
/// radius / its age) over the trunk's (`trunkSpeed`: base radius / age).
void addBranchChain(MeasuredTree& tree, const BranchSpec& s, BuiltChain& c,
                    const BuiltChain& parent, double defaultGamma, double trunkSpeed) {
    size_t node = static_cast<size_t>(s.node);
    ChainProperties props;
    props.deathTime = c.deathTime;
    props.diebackExponent = 1;
    props.gamma = s.gamma > 0 ? s.gamma : defaultGamma;
    if (props.gamma == 0) {
        double end = std::min(tree.age, c.deathTime);
        double branchAge = end - c.times.front();
        double g = branchAge > 1e-9 ? (0.5 * s.internodes[0].diameter / branchAge) / trunkSpeed
                                    : kMaxDerivedGamma;
        props.gamma = std::clamp(g, kMinDerivedGamma, kMaxDerivedGamma);
    }
    uint32_t parentSegment = parent.firstSegment + static_cast<uint32_t>(node == 0 ? 0 : node - 1);
    c.chain = tree.skeleton.addBranch(parentSegment, c.points, c.times, props, c.radii);
    c.firstSegment = tree.skeleton.chain(c.chain).firstSegment;
    tree.chainOfBranch[s.number.key] = c.chain;
}

}  // namespace

MeasuredTree parseMeasuredTree(const nlohmann::json& json, const std::string& file) {
    TopLevel top = readTopLevel(json, file);
    if (top.trunk.is_null())
        throw InputError(file, "trunk", "missing required trunk internode list");
    std::vector<Internode> trunk = readInternodes(top.trunk, file, "trunk", top.unit);
    std::vector<BranchSpec> specs = readBranches(top.branches, file, top.unit);

    // Sa: given, or the one that makes the farthest tip (ignoring bud delays) born at `age`.
    double longest = farthestTipPath(trunk, specs, file);
    MeasuredTree tree;
    tree.elongationSpeed = top.speed > 0 ? top.speed : longest / top.age;
    double speed = tree.elongationSpeed;

    // First pass: lay out every chain (parents first) and find the newest tip's birth time; only
    // the trunk goes into the skeleton yet.
    std::map<std::string, BuiltChain> built;
    BuiltChain t = layOut({0, 0, 0}, 0, trunk, speed);
    tree.skeleton.addTrunk(t.points, t.times, t.radii);
    t.chain = 0;
    t.firstSegment = 0;
    built[""] = t;
    tree.chainOfBranch["trunk"] = 0;
    double newest = t.times.back();
    for (const auto& s : specs) {
        BuiltChain c = layOutBranch(s, built.at(s.number.parentKey()), speed, file);
        newest = std::max(newest, c.times.back());
        built[s.number.key] = std::move(c);
    }
    if (top.age > 0 && newest > top.age + 1e-9) {
        // Only bud delays (start_time) can push a tip past the tree's age.
        throw InputError(file, "age",
                         fmt::format("a branch tip would be born at {:.4g} years, after the tree's "
                                     "age {} (check start_time)",
                                     newest, top.age));
    }
    tree.age = top.age > 0 ? top.age : newest;

    // Second pass: add the branch chains, parents first, with gamma from the diameters where
    // not given.
    double trunkSpeed = 0.5 * trunk[0].diameter / tree.age;
    for (const auto& s : specs)
        addBranchChain(tree, s, built.at(s.number.key), built.at(s.number.parentKey()),
                       top.defaultGamma, trunkSpeed);
    return tree;
}

MeasuredTree loadMeasuredTree(const std::string& path) {
    return parseMeasuredTree(parseJsonFile(path), path);
}

Skeleton loadMeasuredBranches(const std::string& path) { return loadMeasuredTree(path).skeleton; }

}  // namespace nenrin
