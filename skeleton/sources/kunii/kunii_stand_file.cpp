#include "skeleton/sources/kunii/kunii_stand_file.h"

#include <fmt/format.h>

#include <cmath>

#include "util/atomic_output.h"
#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {

namespace {

constexpr int kVersion = 1;

// The per-tree history is stored column by column (compact and easy to plot).
const char* const kColumns[] = {"weight",       "height",      "crown_base",
                                "crown_radius", "stem_radius", "irradiance"};

double& column(TreeYear& y, int c) {
    switch (c) {
        case 0:
            return y.weight;
        case 1:
            return y.height;
        case 2:
            return y.crownBase;
        case 3:
            return y.crownRadius;
        case 4:
            return y.stemRadius;
        default:
            return y.irradiance;
    }
}

nlohmann::json state(const TreeYear& y) {
    TreeYear copy = y;
    nlohmann::json j;
    for (int c = 0; c < 5; ++c) j[kColumns[c]] = column(copy, c);
    return j;
}

nlohmann::json optionsToJson(const StandOptions& o) {
    nlohmann::json j;
    j["trees"] = o.trees;
    j["years"] = o.years;
    j["seed"] = o.seed;
    j["plot_size"] = o.plotSize;
    j["irradiance"] = o.irradiance;
    nlohmann::json schedule = nlohmann::json::array();
    for (const IrradianceKey& k : o.schedule)
        schedule.push_back({{"year", k.year}, {"irradiance", k.irradiance}});
    j["schedule"] = schedule;
    j["law"] = {{"a", o.law.a}, {"b", o.law.b}, {"c", o.law.c},
                {"d", o.law.d}, {"e", o.law.e}, {"f", o.law.f}};
    const KuniiAllometry& A = o.allometry;
    j["allometry"] = {{"max_height", A.maxHeight},
                      {"height_slope", A.heightSlope},
                      {"crown_radius_coefficient", A.crownRadiusCoefficient},
                      {"crown_radius_exponent", A.crownRadiusExponent},
                      {"stem_density", A.stemDensity},
                      {"max_crown_ratio", A.maxCrownRatio},
                      {"min_crown_ratio", A.minCrownRatio}};
    j["crown_density"] = o.crownDensity;
    j["crown_transmission"] = o.crownTransmission;
    j["crown_layers"] = o.crownLayers;
    j["species_min"] = o.speciesMin;
    j["species_max"] = o.speciesMax;
    j["seedling_diameter"] = o.seedlingDiameter;
    j["reference_weight"] = o.referenceWeight;
    j["max_weight"] = o.maxWeight;
    j["germination_attempts"] = o.germinationAttempts;
    j["germination_light"] = o.germinationLight;
    j["years_below_compensation"] = o.yearsBelowCompensation;
    return j;
}

/// Reads the options; every key is required (a stand file records what was simulated).
StandOptions optionsFromJson(JsonReader& r) {
    StandOptions o;
    auto need = [&](const char* key) {
        if (!r.has(key)) throw r.error(key, "missing required key");
    };
    for (const char* key :
         {"trees", "years", "seed", "plot_size", "irradiance", "law", "allometry", "crown_density",
          "crown_transmission", "crown_layers", "species_min", "species_max", "seedling_diameter",
          "reference_weight", "max_weight", "germination_attempts", "germination_light",
          "years_below_compensation"})
        need(key);
    o.trees = static_cast<int>(r.integer("trees", 0, 0, 100000));
    o.years = static_cast<int>(r.integer("years", 0, 0, 10000));
    o.seed = static_cast<uint64_t>(r.integer("seed", 0, 0, (1ll << 53) - 1));
    o.plotSize = r.requirePositive("plot_size");
    o.irradiance = r.nonNegative("irradiance", 0);
    for (JsonReader& k : r.objectList("schedule")) {
        o.schedule.push_back({k.nonNegative("year", 0), k.nonNegative("irradiance", 0)});
        if (!k.has("year")) throw k.error("year", "missing required key");
        if (!k.has("irradiance")) throw k.error("irradiance", "missing required key");
        k.finish();
    }
    auto law = r.object("law");
    o.law.a = law->requirePositive("a");
    o.law.b = law->nonNegative("b", 0);
    o.law.c = law->nonNegative("c", 0);
    o.law.d = law->requireNumber("d");
    o.law.e = law->requirePositive("e");
    o.law.f = law->requirePositive("f");
    for (const char* key : {"b", "c"})
        if (!law->has(key)) throw law->error(key, "missing required key");
    law->finish();
    auto al = r.object("allometry");
    KuniiAllometry& A = o.allometry;
    A.maxHeight = al->requirePositive("max_height");
    A.heightSlope = al->requirePositive("height_slope");
    A.crownRadiusCoefficient = al->requirePositive("crown_radius_coefficient");
    A.crownRadiusExponent = al->requirePositive("crown_radius_exponent");
    A.stemDensity = al->requirePositive("stem_density");
    A.maxCrownRatio = al->requirePositive("max_crown_ratio");
    A.minCrownRatio = al->requirePositive("min_crown_ratio");
    al->finish();
    o.crownDensity = r.requirePositive("crown_density");
    o.crownTransmission = r.requirePositive("crown_transmission");
    o.crownLayers = static_cast<int>(r.integer("crown_layers", 8, 1, 1000));
    o.speciesMin = r.nonNegative("species_min", 0);
    o.speciesMax = r.nonNegative("species_max", 0);
    o.seedlingDiameter = r.requirePositive("seedling_diameter");
    o.referenceWeight = r.requirePositive("reference_weight");
    o.maxWeight = r.requirePositive("max_weight");
    o.germinationAttempts = r.nonNegative("germination_attempts", 0);
    o.germinationLight = r.nonNegative("germination_light", 0);
    o.yearsBelowCompensation = static_cast<int>(r.integer("years_below_compensation", 1, 1, 10000));
    r.finish();
    try {
        validateStandOptions(o);
    } catch (const InputError& e) {
        // Same checks as for the API; here they point into the file.
        throw InputError(r.file(), r.pathOf(e.where()), e.message());
    }
    return o;
}

TreeYear readState(JsonReader& r) {
    TreeYear y;
    for (int c = 0; c < 5; ++c) {
        if (!r.has(kColumns[c])) throw r.error(kColumns[c], "missing required key");
        column(y, c) = r.nonNegative(kColumns[c], 0);
    }
    r.finish();
    return y;
}

}  // namespace

nlohmann::json standToJson(const Stand& stand) {
    nlohmann::json j;
    j["format"] = "nenrin-stand";
    j["version"] = kVersion;
    j["options"] = optionsToJson(stand.options);
    j["irradiance"] = stand.irradiance;
    nlohmann::json trees = nlohmann::json::array();
    for (const StandTree& t : stand.trees) {
        nlohmann::json tj;
        tj["id"] = t.id;
        tj["species"] = t.species;
        tj["position"] = {t.x, t.y};
        tj["birth_year"] = t.birthYear;
        if (!t.alive()) tj["death_year"] = t.deathYear;
        tj["germination_light"] = t.germinationLight;
        tj["initial"] = state(t.initial);
        nlohmann::json history;
        for (int c = 0; c < 6; ++c) {
            nlohmann::json col = nlohmann::json::array();
            for (TreeYear y : t.history) col.push_back(column(y, c));
            history[kColumns[c]] = col;
        }
        tj["history"] = history;
        trees.push_back(tj);
    }
    j["trees"] = trees;
    return j;
}

Stand standFromJson(const nlohmann::json& json, const std::string& file) {
    JsonReader root(json, file);
    if (!root.has("format"))
        throw root.error("format", "missing format tag: expected \"nenrin-stand\"");
    root.choice("format", "nenrin-stand", {"nenrin-stand"});
    root.integer("version", kVersion, kVersion, kVersion);
    Stand stand;
    if (!root.has("options")) throw root.error("options", "missing required key");
    auto options = root.object("options");
    stand.options = optionsFromJson(*options);
    const int years = stand.options.years;
    if (!root.has("irradiance")) throw root.error("irradiance", "missing required key");
    stand.irradiance = root.numberList("irradiance");
    if (static_cast<int>(stand.irradiance.size()) != years)
        throw root.error("irradiance", fmt::format("expected {} values (one per year), found {}",
                                                   years, stand.irradiance.size()));
    for (size_t i = 0; i < stand.irradiance.size(); ++i)
        if (!(stand.irradiance[i] >= 0) || !std::isfinite(stand.irradiance[i]))
            throw root.error("irradiance", fmt::format("entry {} is {}: expected a relative "
                                                       "irradiance >= 0",
                                                       i, stand.irradiance[i]));
    if (!root.has("trees")) throw root.error("trees", "missing required key");
    for (JsonReader& r : root.objectList("trees")) {
        StandTree t;
        for (const char* key :
             {"id", "species", "position", "birth_year", "germination_light", "initial", "history"})
            if (!r.has(key)) throw r.error(key, "missing required key");
        t.id = static_cast<uint32_t>(r.integer("id", 0, 0, 0xffffffffll));
        if (t.id != stand.trees.size())
            throw r.error("id", fmt::format("is {}: expected {} (trees are listed by id)", t.id,
                                            stand.trees.size()));
        t.species = r.requireNumber("species");
        Vec3 position;
        {
            std::vector<double> p = r.numberList("position");
            if (p.size() != 2)
                throw r.error("position",
                              fmt::format("expected [x, y], found {} numbers", p.size()));
            position = {p[0], p[1], 0};
        }
        t.x = position.x;
        t.y = position.y;
        t.birthYear = static_cast<int>(r.integer("birth_year", 0, 0, years));
        // No death_year: the tree was alive at the end.
        t.deathYear = r.has("death_year")
                          ? static_cast<int>(r.integer("death_year", 0, t.birthYear, years - 1))
                          : kStillAlive;
        t.germinationLight = r.requireNumber("germination_light");
        auto initial = r.object("initial");
        t.initial = readState(*initial);
        auto history = r.object("history");
        size_t expected = static_cast<size_t>((t.alive() ? years : t.deathYear) - t.birthYear);
        std::vector<std::vector<double>> columns;
        for (int c = 0; c < 6; ++c) {
            if (!history->has(kColumns[c]))
                throw history->error(kColumns[c], "missing required key");
            columns.push_back(history->numberList(kColumns[c]));
            if (columns.back().size() != expected)
                throw history->error(
                    kColumns[c],
                    fmt::format("expected {} values (years {}..{} of the tree's life), found {}",
                                expected, t.birthYear, t.birthYear + static_cast<int>(expected) - 1,
                                columns.back().size()));
            for (size_t i = 0; i < expected; ++i)
                if (!(columns.back()[i] >= 0) || !std::isfinite(columns.back()[i]))
                    throw history->error(kColumns[c], fmt::format("entry {} is {}: expected a "
                                                                  "finite number >= 0",
                                                                  i, columns.back()[i]));
        }
        history->finish();
        t.history.resize(expected);
        for (size_t i = 0; i < expected; ++i)
            for (int c = 0; c < 6; ++c)
                column(t.history[i], c) = columns[static_cast<size_t>(c)][i];
        for (size_t i = 1; i < expected; ++i)
            if (t.history[i].stemRadius < t.history[i - 1].stemRadius)
                throw history->error("stem_radius",
                                     fmt::format("entry {} ({}) is smaller than entry {} before "
                                                 "it: expected a stem that never shrinks",
                                                 i, t.history[i].stemRadius, i - 1));
        r.finish();
        stand.trees.push_back(std::move(t));
    }
    root.finish();
    return stand;
}

void saveStandFile(const Stand& stand, const std::string& path) {
    nlohmann::json j = standToJson(stand);
    writeTextAtomically(path, j.dump() + '\n', "stand file");
}

Stand loadStandFile(const std::string& path) { return standFromJson(parseJsonFile(path), path); }

}  // namespace nenrin
