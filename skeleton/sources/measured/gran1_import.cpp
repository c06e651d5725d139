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

}  // namespace

Gran1Log importGran1(const std::string& prefix, const Gran1Options& o) {
    if (!(o.rings > 0) || !(o.heightGrowth >= 0) || !(o.branchGrowth > 0) || !(o.knotGamma > 0) ||
        !(o.diebackExponent >= 0))
        throw InputError(prefix, "",
                         "expected rings > 0, height growth >= 0, branch growth > 0, knot gamma "
                         "> 0 and dieback exponent >= 0");
    const std::string pithPath = prefix + "_pith.json", radiiPath = prefix + "_radii.json",
                      knotsPath = prefix + "_knots.json";
    auto pithRows = readTable(pithPath, 3);
    auto radii = readTable(radiiPath, 0);
    auto knotRows = readTable(knotsPath, 9);
    if (pithRows.size() < 2) throw InputError(pithPath, "", "expected at least 2 pith points");
    for (size_t i = 1; i < pithRows.size(); ++i)
        if (!(pithRows[i][2] > pithRows[i - 1][2]))
            throw InputError(pithPath, fmt::format("[{}][2]", i),
                             "expected heights (z, mm) rising from row to row");
    if (radii.size() != pithRows.size())
        throw InputError(radiiPath, "",
                         fmt::format("expected one row per pith point ({}), found {}",
                                     pithRows.size(), radii.size()));

    Gran1Log log;
    // Bark: mean radius per height slice, and its taper by least squares.
    std::vector<double> meanRadius;
    log.minBarkRadius = 1e300;
    for (size_t i = 0; i < radii.size(); ++i) {
        if (radii[i].empty())
            throw InputError(radiiPath, fmt::format("[{}]", i), "expected radii per azimuth");
        double sum = 0;
        for (double r : radii[i]) {
            // At most 10 m: sums of absurd radii once overflowed and wrote null radii.
            if (!(r > 0 && r <= kMaxBarkRadiusMm))
                throw InputError(radiiPath, fmt::format("[{}]", i),
                                 fmt::format("expected bark radii in (0, {:g}] mm, found {:g}",
                                             kMaxBarkRadiusMm, r));
            sum += r;
            log.minBarkRadius = std::min(log.minBarkRadius, r * kMm);
            log.maxBarkRadius = std::max(log.maxBarkRadius, r * kMm);
        }
        meanRadius.push_back(sum / radii[i].size() * kMm);
    }
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

    // Trunk: the pith, moved so that its base is at x = y = z = 0.
    Pith pith;
    std::vector<double> births, trunkRadii;
    const Vec3 base{pithRows[0][0], pithRows[0][1], pithRows[0][2]};
    for (size_t i = 0; i < pithRows.size(); ++i) {
        Vec3 p = (Vec3{pithRows[i][0], pithRows[i][1], pithRows[i][2]} - base) * kMm;
        pith.points.push_back(p);
        births.push_back(p.z / log.heightGrowth);
        trunkRadii.push_back(meanRadius[i]);
    }
    log.skeleton.addTrunk(pith.points, births, trunkRadii);

    // Knots: z(r) = C + D√r + E r, azimuth(r) = F + G ln r, from r = 0 to H; alive while r < I.
    for (size_t k = 0; k < knotRows.size(); ++k) {
        const auto& q = knotRows[k];
        double C = q[2], D = q[3], E = q[4], F = q[5], G = q[6], H = q[7], I = q[8];
        if (I < kDeadAtOnceMm) {
            ++log.knotsSkipped;
            continue;
        }
        if (!(H > 0))
            throw InputError(knotsPath, fmt::format("[{}][7]", k),
                             fmt::format("expected the knot's end distance H > 0 mm, found {}", H));
        double startZ = (C - base.z) * kMm;
        if (startZ < 0 || startZ > pith.points.back().z)
            throw InputError(knotsPath, fmt::format("[{}][2]", k),
                             fmt::format("the knot starts at z = {} mm, off the pith ({} … {} mm)",
                                         C, base.z, pithRows.back()[2]));
        auto [segment, t, origin] = pith.at(startZ);
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
    log.skeleton.setRingWidths(
        std::vector<double>(static_cast<size_t>(std::ceil(o.rings)), log.ringWidth));
    return log;
}

}  // namespace nenrin
