#include "stats_command.h"

#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "renderer/stats/image_statistics.h"
#include "renderer/stats/stats_image.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

struct StatsOptions {
    std::vector<std::string> images;
    std::string against;
    bool rings = false, json = false;
};

/// What --help says each figure is (the script's own words, shortened).
constexpr const char* kFigures =
    R"(Every image is resampled to 256 x 256 first (a 5 cm face: 0.2 mm pixels). PNG, JPEG: sRGB;
EXR: scene-linear R, G, B. The figures (docs/stats.md):
  L*a*b*      mean CIELAB (D65)
  std_L       standard deviation of L*
  fine        std of L* minus L* blurred by a Gaussian of 4 px: fibres, pores, specks (< ~1 mm)
  mid         std of (L* blurred 4 px) minus (L* blurred 16 px): rings, streaks, figure (1-6 mm)
  dir_spread  circular spread (deg) of the local grain direction (structure tensor of L*,
              Gaussians 1.5 and 8 px): 0 for ruler-straight lines, 10-40 for real boards
  fine_aniso  how directional the fine texture is: median ratio of the eigenvalues of its
              structure tensor (16 px); white noise ~1, straight edges ~100, wood 1.3-3.6
--against PHOTO: each IMAGE also against the photo: dE (dE*ab of the mean colours), fine and
  mid as ratios (x), dir_spread as a difference (deg), fine_aniso as a ratio (x).
--rings PHOTO FIELD.exr: the rings seen in the photo against the growth time T of a bake of the
  same plane (same pixel grid): the angle between the photo's ring normals and the gradient of
  T, as the coherence-weighted median (deg) and share of pixels within 15 deg, a 16 px border
  left out.
--json: one JSON object per line, with the keys of the team's photo-stats script.)";

/// One JSON line; a file name that is not UTF-8 is printed with U+FFFD, not refused.
std::string jsonLine(const nlohmann::ordered_json& j) {
    return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

ImageStatistics statisticsOf(const std::string& path) {
    return roundedAsReported(imageStatistics(labPlanes(readStatsRgb(path).linear)));
}

nlohmann::ordered_json toJson(const std::string& path, const ImageStatistics& s,
                              const std::optional<StatisticsAgainst>& vs) {
    nlohmann::ordered_json j = {{"image", path},
                                {"lab", {s.lab[0], s.lab[1], s.lab[2]}},
                                {"std_L", s.stdL},
                                {"fine", s.fine},
                                {"mid", s.mid},
                                {"dir_spread", s.dirSpread},
                                {"fine_aniso", s.fineAniso}};
    if (vs)
        j["vs"] = {{"dE_ab", vs->dE},
                   {"fine_ratio", vs->fineRatio},
                   {"mid_ratio", vs->midRatio},
                   {"dir_spread_diff", vs->dirSpreadDiff},
                   {"fine_aniso_ratio", vs->fineAnisoRatio}};
    return j;
}

std::string toText(const std::string& path, const ImageStatistics& s,
                   const std::optional<StatisticsAgainst>& vs) {
    std::string line = fmt::format(
        "{}: L*a*b* {:.1f} {:.1f} {:.1f}  std_L {:.2f}  fine {:.2f}  mid {:.2f}  dir_spread "
        "{:.1f} deg  fine_aniso {:.2f}",
        path, s.lab[0], s.lab[1], s.lab[2], s.stdL, s.fine, s.mid, s.dirSpread, s.fineAniso);
    if (vs)
        line += fmt::format(
            "  | vs photo: dE {:.1f}, fine x{:.2f}, mid x{:.2f}, dir_spread {:+.1f} deg, "
            "fine_aniso x{:.2f}",
            vs->dE, vs->fineRatio, vs->midRatio, vs->dirSpreadDiff, vs->fineAnisoRatio);
    return line;
}

void runRings(const StatsOptions& o) {
    if (o.images.size() != 2 || !o.against.empty())
        throw InputError("command line", "--rings",
                         fmt::format("expected PHOTO FIELD.exr and no --against, found {} "
                                     "file{}{}",
                                     o.images.size(), o.images.size() == 1 ? "" : "s",
                                     o.against.empty() ? "" : " and --against"));
    const std::string &photo = o.images[0], &field = o.images[1];
    const StatsRgb rgb = readStatsRgb(photo);
    const StatsChannel t = readStatsChannel(field, "T");
    if (t.sourceWidth != rgb.sourceWidth || t.sourceHeight != rgb.sourceHeight)
        throw InputError(
            field, "",
            fmt::format("{}x{} pixels, but {} is {}x{}: expected a bake of the "
                        "photo's plane on its pixel grid",
                        t.sourceWidth, t.sourceHeight, photo, rgb.sourceWidth, rgb.sourceHeight));
    const RingAgreement r = ringAgreement(labPlanes(rgb.linear)[0], t.values, photo);
    if (o.json)
        fmt::print("{}\n", jsonLine({{"photo", photo},
                                     {"field", field},
                                     {"median_deg", r.medianDeg},
                                     {"within_15deg", r.within15}}));
    else
        fmt::print("{} vs {}: ring normals median {:.1f} deg off, {:.0f}% within 15 deg\n", field,
                   photo, r.medianDeg, 100 * r.within15);
}

void runStats(const StatsOptions& o) {
    // Every figure first, so that a bad file stops the command before any line is printed.
    std::optional<ImageStatistics> photo;
    if (!o.against.empty()) photo = statisticsOf(o.against);
    std::vector<ImageStatistics> stats;
    std::vector<std::optional<StatisticsAgainst>> against;
    for (const std::string& path : o.images) {
        stats.push_back(statisticsOf(path));
        against.emplace_back(photo
                                 ? std::optional(statisticsAgainst(stats.back(), *photo, o.against))
                                 : std::nullopt);
    }
    auto print = [&](const std::string& path, const ImageStatistics& s,
                     const std::optional<StatisticsAgainst>& vs) {
        fmt::print("{}\n", o.json ? jsonLine(toJson(path, s, vs)) : toText(path, s, vs));
    };
    if (photo) print(o.against, *photo, std::nullopt);
    for (size_t i = 0; i < o.images.size(); ++i) print(o.images[i], stats[i], against[i]);
}

}  // namespace

void addStatsCommand(CLI::App& app) {
    auto o = std::make_shared<StatsOptions>();
    CLI::App* stats = app.add_subcommand(
        "stats",
        "Wood-photo statistics (docs/stats.md): how an image of wood looks, in numbers, also "
        "against a photograph (--against), or how well a bake's growth time explains a "
        "photograph's rings (--rings)");
    stats->add_option("images", o->images, "Images (PNG, JPEG: sRGB; EXR: linear R, G, B)")
        ->required();
    stats->add_option("--against", o->against,
                      "A photograph to compare each image with (printed first)");
    stats->add_flag("--rings", o->rings,
                    "Ring agreement: the images are PHOTO FIELD.exr (a bake with channel T, "
                    "same plane and pixel grid)");
    stats->add_flag("--json", o->json, "One JSON object per line (the script's keys)");
    stats->footer(kFigures);
    stats->callback([o] { o->rings ? runRings(*o) : runStats(*o); });
}

}  // namespace nenrin
