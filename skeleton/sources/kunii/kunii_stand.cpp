#include "skeleton/sources/kunii/kunii_stand.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "util/hash.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

constexpr double kPi = std::numbers::pi;

/// Shortest offset on the periodic plot (the plot wraps around in x and y).
double wrap(double d, double size) { return d - size * std::round(d / size); }

/// Area of the intersection of two circles of radii r1, r2 whose centres are `dist` apart.
double circleOverlap(double r1, double r2, double dist) {
    if (dist >= r1 + r2) return 0;
    double small = std::min(r1, r2), large = std::max(r1, r2);
    if (dist <= large - small) return kPi * small * small;
    double a1 = std::acos(std::clamp((dist * dist + r1 * r1 - r2 * r2) / (2 * dist * r1), -1., 1.));
    double a2 = std::acos(std::clamp((dist * dist + r2 * r2 - r1 * r1) / (2 * dist * r2), -1., 1.));
    double kite = 0.5 * std::sqrt(std::max(0.0, (-dist + r1 + r2) * (dist + r1 - r2) *
                                                    (dist - r1 + r2) * (dist + r1 + r2)));
    return r1 * r1 * a1 + r2 * r2 * a2 - kite;
}

void require(bool ok, const std::string& parameter, const std::string& expected, double value) {
    if (!ok)
        throw InputError("stand options", parameter,
                         fmt::format("is {}: expected {}", value, expected));
}

/// What the light pass hands to the growth pass for one tree.
struct CrownLight {
    double irradiance = 0;  ///< crown-mean irradiance, eq. 1's I
    double crownBase = 0;   ///< after shedding the layers below the compensation point
};

/// A living tree's crown at the start of the year, flattened for the light pass.
struct Crown {
    double x, y, radius, top, base;
};

class StandSimulation {
public:
    explicit StandSimulation(const StandOptions& o) : o_(o), rng_(mix64(o.seed ^ 0x6b756e6969ull)) {
        stand_.options = o;
    }

    Stand run(const std::function<void(int, int)>& progress) {
        for (int i = 0; i < o_.trees; ++i)
            plant(rng_.uniform() * o_.plotSize, rng_.uniform() * o_.plotSize, 0, -1);
        int attempts = static_cast<int>(
            std::lround(o_.germinationAttempts * o_.plotSize * o_.plotSize / 100.0));
        for (int year = 0; year < o_.years; ++year) {
            double I0 = o_.irradianceAt(year);
            stand_.irradiance.push_back(I0);
            step(year, I0);
            if (year + 1 < o_.years) germinate(year + 1, I0, attempts);
            if (progress) progress(year + 1, o_.years);
        }
        return std::move(stand_);
    }

private:
    void plant(double x, double y, int birthYear, double light) {
        StandTree t;
        t.id = static_cast<uint32_t>(stand_.trees.size());
        t.species = o_.speciesMin + (o_.speciesMax - o_.speciesMin) * rng_.uniform();
        t.x = x;
        t.y = y;
        t.birthYear = birthYear;
        t.germinationLight = light;
        const KuniiAllometry& A = o_.allometry;
        double D = o_.seedlingDiameter;
        t.initial.weight = A.weight(D);
        t.initial.height = A.height(D);
        t.initial.crownRadius = A.crownRadius(D);
        t.initial.crownBase = t.initial.height * (1 - A.maxCrownRatio);
        t.initial.stemRadius = D / 2;
        living_.push_back(t.id);
        below_.push_back(0);
        stand_.trees.push_back(std::move(t));
    }

    std::vector<Crown> crowns() const {
        std::vector<Crown> c;
        c.reserve(living_.size());
        for (uint32_t id : living_) {
            const StandTree& t = stand_.trees[id];
            const TreeYear& s = t.last();
            c.push_back({t.x, t.y, s.crownRadius, s.height, s.crownBase});
        }
        return c;
    }

    /// Eq. 4 integrated over the crown in layers, minus each overlapping neighbour's shade
    /// (the paper's sum of separate shades), then the bottom layers below the compensation
    /// point are shed.
    CrownLight crownLight(size_t i, const std::vector<Crown>& crowns, double I0,
                          double compensation, std::vector<double>& layerLight,
                          std::vector<std::pair<double, size_t>>& overlaps) const {
        const Crown& me = crowns[i];
        overlaps.clear();
        for (size_t j = 0; j < crowns.size(); ++j) {
            if (j == i) continue;
            const Crown& other = crowns[j];
            if (other.top <= me.base) continue;  // entirely below: casts no shade on us
            double dx = wrap(other.x - me.x, o_.plotSize), dy = wrap(other.y - me.y, o_.plotSize);
            double reach = me.radius + other.radius;
            if (dx * dx + dy * dy >= reach * reach) continue;
            double area = circleOverlap(me.radius, other.radius, std::sqrt(dx * dx + dy * dy));
            if (area > 0) overlaps.emplace_back(area, j);
        }
        const double t = o_.crownDensity, top = o_.crownTransmission * I0;
        const double area = kPi * me.radius * me.radius;
        const int n = o_.crownLayers;
        const double depth = me.top - me.base, dz = depth / n;
        layerLight.assign(static_cast<size_t>(n), 0.0);
        for (int m = 0; m < n; ++m) {
            double h = me.base + (m + 0.5) * dz;
            double open = top * std::exp(-t * (me.top - h));  // eq. 4
            double light = area * open;
            for (const auto& [overlap, j] : overlaps) {
                const Crown& other = crowns[j];
                double leavesAbove = other.top - std::max(h, other.base);
                if (leavesAbove > 0) light -= overlap * open * (1 - std::exp(-t * leavesAbove));
            }
            layerLight[static_cast<size_t>(m)] = std::max(0.0, light / area);
        }
        // Shed the bottom layers that cannot pay for themselves, keeping a minimal crown.
        double minDepth = o_.allometry.minCrownRatio * me.top;
        int first = 0;
        while (first < n - 1 && layerLight[static_cast<size_t>(first)] <= compensation &&
               depth - (first + 1) * dz >= minDepth)
            ++first;
        double sum = 0;
        for (int m = first; m < n; ++m) sum += layerLight[static_cast<size_t>(m)];
        return {sum / (n - first), me.base + first * dz};
    }

    void step(int year, double I0) {
        std::vector<Crown> crown = crowns();
        std::vector<CrownLight> light(living_.size());
        std::vector<double> layers;
        std::vector<std::pair<double, size_t>> overlaps;
        for (size_t i = 0; i < living_.size(); ++i) {
            const StandTree& t = stand_.trees[living_[i]];
            light[i] = crownLight(i, crown, I0, compensationIrradiance(o_.law, t.species), layers,
                                  overlaps);
        }
        std::vector<uint32_t> stillLiving;
        std::vector<int> stillBelow;
        for (size_t i = 0; i < living_.size(); ++i) {
            StandTree& t = stand_.trees[living_[i]];
            bool belowCompensation =
                light[i].irradiance <= compensationIrradiance(o_.law, t.species);
            int below = belowCompensation ? below_[i] + 1 : 0;
            if (below >= o_.yearsBelowCompensation) {
                t.deathYear = year;
                continue;
            }
            t.history.push_back(grow(t, light[i], belowCompensation));
            stillLiving.push_back(living_[i]);
            stillBelow.push_back(below);
        }
        living_ = std::move(stillLiving);
        below_ = std::move(stillBelow);
    }

    TreeYear grow(const StandTree& t, const CrownLight& light, bool belowCompensation) const {
        const KuniiAllometry& A = o_.allometry;
        TreeYear s = t.last();
        s.irradiance = light.irradiance;
        s.crownBase = std::max(s.crownBase, light.crownBase);
        if (!belowCompensation) {
            // Eq. 1 is the rate of a reference tree; bigger trees grow relatively slower
            // (w^-1/4) and stop at maxWeight: the ontogenetic growth curve of West, Brown &
            // Enquist (2001), dw/dt ~ w^3/4 (1 - (w/M)^1/4).
            double w = s.weight;
            double rate = relativeGrowthRate(o_.law, t.species, light.irradiance) *
                          std::pow(w / o_.referenceWeight, -0.25) *
                          std::max(0.0, 1 - std::pow(w / o_.maxWeight, 0.25));
            s.weight = w * std::exp(rate);
            double D = A.diameter(s.weight);
            s.height = std::max(s.height, A.height(D));
            s.crownRadius = std::max(s.crownRadius, A.crownRadius(D));
            s.stemRadius = std::max(s.stemRadius, D / 2);
        }
        s.crownBase = std::max(s.crownBase, s.height * (1 - A.maxCrownRatio));
        return s;
    }

    void germinate(int birthYear, double I0, int attempts) {
        std::vector<Crown> crown = crowns();
        for (int k = 0; k < attempts; ++k) {
            double x = rng_.uniform() * o_.plotSize, y = rng_.uniform() * o_.plotSize;
            double transmitted = 1;
            for (const Crown& c : crown) {
                double dx = wrap(c.x - x, o_.plotSize), dy = wrap(c.y - y, o_.plotSize);
                if (dx * dx + dy * dy < c.radius * c.radius)
                    transmitted -= 1 - std::exp(-o_.crownDensity * (c.top - c.base));
            }
            double light = I0 * std::max(0.0, transmitted);
            if (light > o_.germinationLight) plant(x, y, birthYear, light);
        }
    }

    const StandOptions& o_;
    SplitMix rng_;
    Stand stand_;
    std::vector<uint32_t> living_;  ///< ids of the living trees, in id order
    std::vector<int> below_;        ///< per living tree: consecutive years below compensation
};

}  // namespace

double KuniiAllometry::height(double D) const {
    return maxHeight * (1 - std::exp(-heightSlope * D / maxHeight));
}

double KuniiAllometry::crownRadius(double D) const {
    return crownRadiusCoefficient * std::pow(D, crownRadiusExponent);
}

double KuniiAllometry::weight(double D) const { return stemDensity * kPi / 4 * D * D * height(D); }

double KuniiAllometry::diameter(double w) const {
    double lo = 0, hi = 1;
    while (weight(hi) < w && hi < 1e3) hi *= 2;
    for (int i = 0; i < 60; ++i) {
        double mid = 0.5 * (lo + hi);
        (weight(mid) < w ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double StandOptions::irradianceAt(double year) const {
    if (schedule.empty()) return irradiance;
    if (year <= schedule.front().year) return schedule.front().irradiance;
    for (size_t i = 1; i < schedule.size(); ++i) {
        const IrradianceKey &a = schedule[i - 1], &b = schedule[i];
        if (year <= b.year) {
            double u = b.year > a.year ? (year - a.year) / (b.year - a.year) : 1.0;
            return a.irradiance + (b.irradiance - a.irradiance) * u;
        }
    }
    return schedule.back().irradiance;
}

StandOptions standPreset(const std::string& name) {
    StandOptions o;
    if (name == "tropical") return o;
    if (name == "shade") {
        o.irradiance = 0.3;
        return o;
    }
    if (name == "cooling" || name == "warming") {
        o.years = 120;
        double start = name == "cooling" ? 1.0 : 0.25;
        o.schedule = {{0, start}, {50, start}, {60, 0.35}};
        o.irradiance = 0.35;
        return o;
    }
    throw InputError("stand options", "preset",
                     fmt::format("unknown preset \"{}\": expected one of tropical, shade, "
                                 "cooling, warming",
                                 name));
}

std::vector<std::string> standPresetNames() { return {"tropical", "shade", "cooling", "warming"}; }

void validateStandOptions(const StandOptions& o) {
    auto finite = [](double v) { return std::isfinite(v); };
    require(o.trees >= 0 && o.trees <= 100000, "trees", "a count in 0..100000", o.trees);
    require(o.years >= 0 && o.years <= 10000, "years", "a count of years in 0..10000", o.years);
    require(o.seed < (1ull << 53), "seed", "a seed below 2^53 (exact in JSON files)",
            static_cast<double>(o.seed));
    require(finite(o.plotSize) && o.plotSize > 0, "plot_size", "a side > 0 (m)", o.plotSize);
    require(finite(o.irradiance) && o.irradiance >= 0, "irradiance", "a relative irradiance >= 0",
            o.irradiance);
    for (size_t i = 0; i < o.schedule.size(); ++i) {
        const IrradianceKey& k = o.schedule[i];
        std::string at = fmt::format("schedule[{}]", i);
        require(finite(k.year) && k.year >= 0, at + ".year", "a year >= 0", k.year);
        require(finite(k.irradiance) && k.irradiance >= 0, at + ".irradiance",
                "a relative irradiance >= 0", k.irradiance);
        if (i > 0)
            require(k.year > o.schedule[i - 1].year, at + ".year",
                    "years that increase along the schedule", k.year);
    }
    const KuniiGrowthLaw& L = o.law;
    require(finite(L.a) && L.a > 0, "law.a", "a rate > 0 (1/year)", L.a);
    require(finite(L.b) && L.b >= 0, "law.b", "a number >= 0", L.b);
    require(finite(L.c) && L.c >= 0, "law.c", "a number >= 0", L.c);
    require(finite(L.d), "law.d", "a finite number", L.d);
    require(finite(L.e) && L.e > 0, "law.e", "a number > 0", L.e);
    require(finite(L.f) && L.f > 0, "law.f", "a number > 0", L.f);
    const KuniiAllometry& A = o.allometry;
    require(finite(A.maxHeight) && A.maxHeight > 0, "allometry.max_height", "a height > 0 (m)",
            A.maxHeight);
    require(finite(A.heightSlope) && A.heightSlope > 0, "allometry.height_slope",
            "a number > 0 (m/m)", A.heightSlope);
    require(finite(A.crownRadiusCoefficient) && A.crownRadiusCoefficient > 0,
            "allometry.crown_radius_coefficient", "a radius > 0 (m)", A.crownRadiusCoefficient);
    require(finite(A.crownRadiusExponent) && A.crownRadiusExponent > 0,
            "allometry.crown_radius_exponent", "a number > 0", A.crownRadiusExponent);
    require(finite(A.stemDensity) && A.stemDensity > 0, "allometry.stem_density",
            "a density > 0 (kg/m^3)", A.stemDensity);
    require(finite(A.maxCrownRatio) && A.maxCrownRatio > 0 && A.maxCrownRatio <= 1,
            "allometry.max_crown_ratio", "a ratio in (0, 1]", A.maxCrownRatio);
    require(finite(A.minCrownRatio) && A.minCrownRatio > 0 && A.minCrownRatio <= A.maxCrownRatio,
            "allometry.min_crown_ratio", "a ratio in (0, max_crown_ratio]", A.minCrownRatio);
    require(finite(o.crownDensity) && o.crownDensity > 0, "crown_density",
            "an attenuation > 0 (1/m)", o.crownDensity);
    require(finite(o.crownTransmission) && o.crownTransmission > 0 && o.crownTransmission <= 1,
            "crown_transmission", "k in (0, 1]", o.crownTransmission);
    require(o.crownLayers >= 1 && o.crownLayers <= 1000, "crown_layers", "a count in 1..1000",
            o.crownLayers);
    require(finite(o.speciesMin) && finite(o.speciesMax) && o.speciesMin >= 0 &&
                o.speciesMin <= o.speciesMax,
            "species_min", "0 <= species_min <= species_max", o.speciesMin);
    require(finite(o.seedlingDiameter) && o.seedlingDiameter > 0, "seedling_diameter",
            "a diameter > 0 (m)", o.seedlingDiameter);
    require(finite(o.referenceWeight) && o.referenceWeight > 0, "reference_weight",
            "a weight > 0 (kg)", o.referenceWeight);
    require(finite(o.maxWeight) && o.maxWeight > A.weight(o.seedlingDiameter), "max_weight",
            "a weight (kg) above a seedling's", o.maxWeight);
    require(finite(o.germinationAttempts) && o.germinationAttempts >= 0, "germination_attempts",
            "a count >= 0 (per 100 m^2 and year)", o.germinationAttempts);
    require(finite(o.germinationLight) && o.germinationLight >= 0, "germination_light",
            "a relative irradiance >= 0", o.germinationLight);
    require(o.yearsBelowCompensation >= 1, "years_below_compensation", "a count >= 1",
            o.yearsBelowCompensation);
}

Stand simulateStand(const StandOptions& options,
                    const std::function<void(int year, int years)>& progress) {
    validateStandOptions(options);
    return StandSimulation(options).run(progress);
}

const TreeYear* treeStateAt(const StandTree& tree, int year) {
    int k = year - tree.birthYear;
    if (k < 0 || k >= static_cast<int>(tree.history.size())) return nullptr;
    return &tree.history[static_cast<size_t>(k)];
}

StandComposition standComposition(const Stand& stand, double split, int year) {
    if (year < 0) year = stand.options.years - 1;
    StandComposition c;
    double weighted = 0;
    for (const StandTree& t : stand.trees) {
        const TreeYear* s = treeStateAt(t, year);
        if (!s) continue;
        ++c.living;
        (t.species < split ? c.tolerantWeight : c.intolerantWeight) += s->weight;
        weighted += s->weight * t.species;
    }
    double total = c.tolerantWeight + c.intolerantWeight;
    c.meanSpecies = total > 0 ? weighted / total : 0;
    return c;
}

double groundLight(const Stand& stand, double x, double y, int year) {
    const StandOptions& o = stand.options;
    double transmitted = 1;
    for (const StandTree& t : stand.trees) {
        const TreeYear* s = treeStateAt(t, year);
        if (!s) continue;
        double dx = wrap(t.x - x, o.plotSize), dy = wrap(t.y - y, o.plotSize);
        if (dx * dx + dy * dy < s->crownRadius * s->crownRadius)
            transmitted -= 1 - std::exp(-o.crownDensity * (s->height - s->crownBase));
    }
    return o.irradianceAt(year) * std::max(0.0, transmitted);
}

}  // namespace nenrin
