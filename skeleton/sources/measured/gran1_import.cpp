#include "skeleton/sources/measured/gran1_import.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "util/json_reader.h"

namespace nenrin {

namespace {

constexpr double kMm = 1e-3;
/// Knots that died closer to the pith than this are skipped, as in the publishing code.
constexpr double kDeadAtOnceMm = 0.1;
/// Radial step along a knot curve (mm): fine enough that the polyline follows z = C + D√r.
constexpr double kKnotStepMm = 5;
/// The thickest trunks are ~5 m in radius.
constexpr double kMaxBarkRadiusMm = 10000;

std::vector<std::vector<double>> readTable(const std::string& path, size_t columns) {
    nlohmann::json j = parseJsonFile(path);
    if (!j.is_array() || j.empty())
        throw InputError(path, "",
                         fmt::format("expected an array of rows, found {}",
                                     j.is_array() ? "an empty array" : jsonTypeName(j)));
    std::vector<std::vector<double>> rows;
    for (size_t i = 0; i < j.size(); ++i) {
        const auto& row = j[i];
        if (!row.is_array() || (columns && row.size() != columns))
            throw InputError(path, fmt::format("[{}]", i),
                             fmt::format("expected a row of {} numbers", columns));
        std::vector<double> values;
        for (size_t c = 0; c < row.size(); ++c) {
            if (!row[c].is_number() || !std::isfinite(row[c].get<double>()))
                throw InputError(
                    path, fmt::format("[{}][{}]", i, c),
                    fmt::format("expected a finite number, found {}", jsonTypeName(row[c])));
            if (std::abs(row[c].get<double>()) > kMaxJsonMagnitude)
                throw InputError(path, fmt::format("[{}][{}]", i, c),
                                 fmt::format("{:g} is beyond the ±{:g} of a measured log (mm, "
                                             "degrees)",
                                             row[c].get<double>(), kMaxJsonMagnitude));
            values.push_back(row[c].get<double>());
        }
        rows.push_back(std::move(values));
    }
    return rows;
}

struct Pith {
    std::vector<Vec3> points;  // m, tree space (base of the pith at x = y = 0)

    struct Place {
        uint32_t segment;
        double t;  ///< 0..1 along the segment
        Vec3 point;
    };
    /// The trunk segment containing height z (m) and the pith point there.
    Place at(double z) const {
        for (size_t i = 0; i + 1 < points.size(); ++i) {
            double z0 = points[i].z, z1 = points[i + 1].z;
            if (z <= z1 || i + 2 == points.size()) {
                double t = std::clamp((z - z0) / (z1 - z0), 0.0, 1.0);
                return {static_cast<uint32_t>(i), t, lerp(points[i], points[i + 1], t)};
            }
        }
        return {0, 0, points[0]};
    }
};

using Table = std::vector<std::vector<double>>;

struct Gran1Tables {
    std::string pithPath, radiiPath, knotsPath;
    Table pith;   ///< x, y, z (mm) per row, z rising
    Table radii;  ///< bark radius (mm) per azimuth, one row per pith point
    Table knots;  ///< A … I per knot (mm, radians; docs/trees.md, "Gran_1 CT-measured logs")
};

void checkOptions(const std::string& prefix, const Gran1Options& o) {
    if (!(o.rings > 0) || !(o.heightGrowth >= 0) || !(o.branchGrowth > 0) || !(o.knotGamma > 0) ||
        !(o.diebackExponent >= 0))
        throw InputError(prefix, "",
                         "expected rings > 0, height growth >= 0, branch growth > 0, knot gamma "
                         "> 0 and dieback exponent >= 0");
}

/// The three files, with the pith's rows and the radii's rows checked against each other.
Gran1Tables readTables(const std::string& prefix) {
    Gran1Tables t;
    t.pithPath = prefix + "_pith.json";
    t.radiiPath = prefix + "_radii.json";
    t.knotsPath = prefix + "_knots.json";
    t.pith = readTable(t.pithPath, 3);
    t.radii = readTable(t.radiiPath, 0);
    t.knots = readTable(t.knotsPath, 9);
    if (t.pith.size() < 2) throw InputError(t.pithPath, "", "expected at least 2 pith points");
    for (size_t i = 1; i < t.pith.size(); ++i)
        if (!(t.pith[i][2] > t.pith[i - 1][2]))
            throw InputError(t.pithPath, fmt::format("[{}][2]", i),
                             "expected heights (z, mm) rising from row to row");
    if (t.radii.size() != t.pith.size())
        throw InputError(t.radiiPath, "",
                         fmt::format("expected one row per pith point ({}), found {}",
                                     t.pith.size(), t.radii.size()));
    return t;
}

/// The bark's mean radius (m) per height slice; sets the log's least and greatest bark radius.
std::vector<double> meanBarkRadii(const Gran1Tables& t, Gran1Log& log) {
    std::vector<double> meanRadius;
    log.minBarkRadius = 1e300;
    for (size_t i = 0; i < t.radii.size(); ++i) {
        if (t.radii[i].empty())
            throw InputError(t.radiiPath, fmt::format("[{}]", i), "expected radii per azimuth");
        double sum = 0;
        for (double r : t.radii[i]) {
            // At most 10 m: sums of absurd radii once overflowed and wrote null radii.
            if (!(r > 0 && r <= kMaxBarkRadiusMm))
                throw InputError(t.radiiPath, fmt::format("[{}]", i),
                                 fmt::format("expected bark radii in (0, {:g}] mm, found {:g}",
                                             kMaxBarkRadiusMm, r));
            sum += r;
            log.minBarkRadius = std::min(log.minBarkRadius, r * kMm);
            log.maxBarkRadius = std::max(log.maxBarkRadius, r * kMm);
        }
        meanRadius.push_back(sum / t.radii[i].size() * kMm);
    }
    return meanRadius;
}

/// The bark's taper by least squares, and from it the butt and top radii, the ring width
/// (butt radius over the rings) and, unless given, the height growth.
void fitTaper(const std::vector<double>& meanRadius, const Table& pithRows, const Gran1Options& o,
              Gran1Log& log) {
    double n = static_cast<double>(meanRadius.size()), sz = 0, sr = 0, szz = 0, szr = 0;
    for (size_t i = 0; i < meanRadius.size(); ++i) {
        double z = (pithRows[i][2] - pithRows[0][2]) * kMm;
        sz += z, sr += meanRadius[i], szz += z * z, szr += z * meanRadius[i];
    }
    double taper = -(n * szr - sz * sr) / (n * szz - sz * sz);  // m of radius lost per m up
    double buttRadius = (sr - (-taper) * sz) / n;               // fitted radius at z = 0
    log.meanButtRadius = buttRadius;
    log.meanTopRadius = buttRadius - taper * (pithRows.back()[2] - pithRows[0][2]) * kMm;
    log.ringWidth = buttRadius / o.rings;
    log.fellingAge = o.rings;
    log.heightGrowth = o.heightGrowth > 0
                           ? o.heightGrowth
                           : std::clamp(taper > 0 ? log.ringWidth / taper : 1.0, 0.1, 1.0);
}

struct Trunk {
    Pith pith;
    std::vector<double> births;  ///< per pith point
    Vec3 base;                   ///< mm: the first pith point in the file's coordinates
};

/// The trunk: the pith, moved so that its base is at x = y = z = 0.
Trunk addTrunk(const Table& pithRows, const std::vector<double>& meanRadius, Gran1Log& log) {
    Trunk trunk;
    std::vector<double> trunkRadii;
    trunk.base = Vec3{pithRows[0][0], pithRows[0][1], pithRows[0][2]};
    for (size_t i = 0; i < pithRows.size(); ++i) {
        Vec3 p = (Vec3{pithRows[i][0], pithRows[i][1], pithRows[i][2]} - trunk.base) * kMm;
        trunk.pith.points.push_back(p);
        trunk.births.push_back(p.z / log.heightGrowth);
        trunkRadii.push_back(meanRadius[i]);
    }
    log.skeleton.addTrunk(trunk.pith.points, trunk.births, trunkRadii);
    return trunk;
}

/// Knot k: z(r) = C + D√r + E r, azimuth(r) = F + G ln r, from r = 0 to H; alive while r < I.
void addKnot(const Gran1Tables& tables, size_t k, const Trunk& trunk, const Gran1Options& o,
             Gran1Log& log) {
    const auto& q = tables.knots[k];
    const Vec3& base = trunk.base;
    double C = q[2], D = q[3], E = q[4], F = q[5], G = q[6], H = q[7], I = q[8];
    if (I < kDeadAtOnceMm) {
        ++log.knotsSkipped;
        return;
    }
    if (!(H > 0))
        throw InputError(tables.knotsPath, fmt::format("[{}][7]", k),
                         fmt::format("expected the knot's end distance H > 0 mm, found {}", H));
    double startZ = (C - base.z) * kMm;
    if (startZ < 0 || startZ > trunk.pith.points.back().z)
        throw InputError(tables.knotsPath, fmt::format("[{}][2]", k),
                         fmt::format("the knot starts at z = {} mm, off the pith ({} … {} mm)", C,
                                     base.z, tables.pith.back()[2]));
    auto [segment, t, origin] = trunk.pith.at(startZ);
    const std::vector<double>& births = trunk.births;
    double t0 = births[segment] + (births[segment + 1] - births[segment]) * t;
    std::vector<Vec3> points{origin};
    std::vector<double> knotBirths{t0};
    int steps = std::max(2, static_cast<int>(std::ceil(H / kKnotStepMm)));
    for (int s = 1; s <= steps; ++s) {
        double r = H * s / steps;
        double z = C + D * std::sqrt(r) + E * r, az = F + G * std::log(r);
        Vec3 p = origin + Vec3{std::cos(az) * r, std::sin(az) * r, 0} * kMm;
        p.z = (z - base.z) * kMm;
        points.push_back(p);
        knotBirths.push_back(t0 + r * kMm / o.branchGrowth);
    }
    // The stem at this height reached the knot's death distance I after I / ring width
    // years; then the branch died and the stem grew over it.
    double deathTime = t0 + I * kMm / log.ringWidth;
    ChainProperties props{o.knotGamma, I >= H ? kNeverDies : deathTime, o.diebackExponent};
    // A knot's radius: what the branch had grown to by the stem's felling, or its death.
    double lifeEnd = std::min(deathTime, log.fellingAge);
    std::vector<double> knotRadii;
    for (double birth : knotBirths)
        knotRadii.push_back(std::max(0.0, (lifeEnd - birth) * log.ringWidth * o.knotGamma));
    log.skeleton.addBranch(segment, points, knotBirths, props, knotRadii);
    ++log.knots;
}

}  // namespace

Gran1Log importGran1(const std::string& prefix, const Gran1Options& o) {
    checkOptions(prefix, o);
    const Gran1Tables tables = readTables(prefix);
    Gran1Log log;
    // Bark: mean radius per height slice, and its taper by least squares.
    std::vector<double> meanRadius = meanBarkRadii(tables, log);
    fitTaper(meanRadius, tables.pith, o, log);
    Trunk trunk = addTrunk(tables.pith, meanRadius, log);
    for (size_t k = 0; k < tables.knots.size(); ++k) addKnot(tables, k, trunk, o, log);
    log.skeleton.setRingWidths(
        std::vector<double>(static_cast<size_t>(std::ceil(o.rings)), log.ringWidth));
    return log;
}

}  // namespace nenrin
