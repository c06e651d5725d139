#include "ring_series_command.h"

#include <fmt/format.h>

#include <memory>
#include <string>

#include "arguments.h"
#include "skeleton/ring_series.h"
#include "skeleton/skeleton_file.h"
#include "util/atomic_output.h"
#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {

namespace {

struct RingOptions {
    std::string input, series, skeleton, output, latewood;
    bool list = false;
    double meanWidthMm = 0;
};

void listSeries(const RingSeriesFile& file) {
    size_t bad = 0;
    for (const auto& s : file.series) bad += s.bad();
    fmt::print("{}: {} series{}\n", file.path, file.series.size(),
               bad ? fmt::format(", {} of them bad (marked BAD: --series refuses them)", bad)
                   : std::string());
    fmt::print("{:<10} {:>6} {:>6} {:>6} {:>8} {:>9} {:>5} {:>6} {:>6}\n", "series", "first",
               "last", "rings", "unit mm", "mean mm", "CV", "AR1", "MS");
    for (const auto& s : file.series) {
        if (s.bad()) {
            fmt::print("{:<10} {:>6} BAD line {}: {}\n", s.id, s.firstYear, s.problemLine,
                       s.problem);
            continue;
        }
        RingStatistics st = ringStatistics(s.widthsMm);
        fmt::print("{:<10} {:>6} {:>6} {:>6} {:>8} {:>9.3f} {:>5.2f} {:>6.2f} {:>6.2f}\n", s.id,
                   s.firstYear, s.lastYear(), s.widthsMm.size(), s.unitMm, st.mean, st.cv,
                   st.autocorrelation, st.meanSensitivity);
    }
}

void writeSkeletonWithSeries(const RingOptions& o, const RingSeriesFile& file) {
    if (o.skeleton.empty() || o.output.empty())
        throw InputError("command line", "--series",
                         "expected --skeleton S.json and -o OUT.json with --series");
    checkOutputName(o.output, {".json"});
    RingSeries series = file.find(o.series);
    std::vector<double> shares;
    if (!o.latewood.empty()) {
        // FILE is the earlywood of the cores, --latewood their latewood: total widths and
        // each year's latewood share.
        RingSeriesFile late = readTucsonRwl(o.latewood);
        shares = latewoodShares(series, late);
        series = totalFromEarlyLate(series, late);
    }
    std::vector<double> widths = ringWidthsMetres(series, o.meanWidthMm, file.path);

    // The skeleton file keeps its own layout; only its ring widths are replaced.
    nlohmann::json json = parseJsonFile(o.skeleton);
    if (!json.is_object())
        throw InputError(o.skeleton, "", "expected a skeleton file (a JSON object)");
    json.erase("ring_series");
    json["ring_widths"] = widths;
    if (!shares.empty())
        json["latewood_shares"] = shares;
    else
        json.erase("latewood_shares");
    nlohmann::json source = json.contains("source") && json["source"].is_object()
                                ? json["source"]
                                : nlohmann::json::object();
    source["ring_series"] = {{"file", file.path},
                             {"series", series.id},
                             {"first_year", series.firstYear},
                             {"last_year", series.lastYear()},
                             {"mean_width_mm", o.meanWidthMm},
                             {"latewood_file", o.latewood}};
    json["source"] = source;
    Skeleton checked = parseSkeleton(json, o.skeleton);  // still a valid skeleton

    writeTextAtomically(o.output, json.dump(2) + '\n', "skeleton file");
    double radius = 0;
    for (double w : widths) radius += w;
    fmt::print("wrote {}: series {} ({}-{}, {} rings, {:.1f} mm of radius), {} segments\n",
               o.output, series.id, series.firstYear, series.lastYear(), widths.size(),
               radius * 1e3, checked.segments().size());
}

void runRings(const RingOptions& o) {
    if (o.list == !o.series.empty())
        throw InputError("command line", "--list",
                         "expected either --list or --series ID (with --skeleton and -o)");
    RingSeriesFile file = readTucsonRwl(o.input);
    if (o.list)
        listSeries(file);
    else
        writeSkeletonWithSeries(o, file);
}

}  // namespace

void addRingSeriesCommand(CLI::App& tree) {
    auto o = std::make_shared<RingOptions>();
    CLI::App* rings = tree.add_subcommand(
        "rings", "Measured ring-width series (Tucson .rwl): list them, or give one to a skeleton");
    rings->add_option("file", o->input, "Tucson decadal ring-width file (.rwl)")->required();
    rings->add_flag("--list", o->list, "Print each series: ID, first and last year, ring count");
    rings->add_option("--series", o->series, "The series (core) ID to use as ring widths");
    rings->add_option("--skeleton", o->skeleton, "Skeleton file that gets the ring widths");
    rings->add_option("-o,--output", o->output, "Output skeleton file (.json)");
    rings->add_option("--latewood", o->latewood,
                      "Latewood file of the same cores: FILE is then their earlywood, and each "
                      "year gets its own latewood share");
    rings
        ->add_option("--mean-width", o->meanWidthMm,
                     "Scale the series to this mean ring width, mm (0 = as measured)")
        ->check(finiteRange(0.0, 100.0))
        ->default_val(0);
    rings->callback([o] { runRings(*o); });
}

}  // namespace nenrin
