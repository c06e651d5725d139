#include "grain_command.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <string>

#include "grain/colour_strip.h"
#include "grain/grain_params.h"
#include "renderer/image_file.h"
#include "util/atomic_output.h"
#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {

namespace {

struct StripOptions {
    std::string input, output, base;
};

/// The strip's colour per column (rows averaged), scene-linear: 8- and 16-bit images are read
/// as sRGB, float images (EXR) as linear.
std::vector<Rgb> readStrip(const std::string& path) {
    const ImageFile image = readImageFile(path);
    struct {
        int width, height, nchannels;
    } spec{image.width, image.height, image.channels};
    if (spec.nchannels < 3)
        throw InputError(path, "",
                         fmt::format("{} channels: expected an RGB image", spec.nchannels));
    if (spec.width < 32 || spec.height < 1 || spec.width > 100000)
        throw InputError(path, "",
                         fmt::format("{}x{} pixels: expected a strip 32 to 100000 "
                                     "pixels long, pith on the left",
                                     spec.width, spec.height));
    const bool srgb = !image.floatingPoint;
    std::vector<Rgb> columns(size_t(spec.width));
    for (int x = 0; x < spec.width; ++x) {
        Rgb sum;
        for (int y = 0; y < spec.height; ++y) {
            const float* px = &image.pixels[(size_t(y) * spec.width + x) * spec.nchannels];
            Rgb c{px[0], px[1], px[2]};
            if (srgb) c = linearFromSrgb(c);
            if (!std::isfinite(c.r + c.g + c.b))
                throw InputError(path, fmt::format("pixel ({}, {})", x, y), "not a finite colour");
            sum = sum + c;
        }
        columns[size_t(x)] = sum * (1.0 / spec.height);
    }
    return columns;
}

nlohmann::json rgb(const Rgb& c) {
    auto r = [](double v) { return std::round(v * 1e4) / 1e4; };
    return {r(c.r), r(c.g), r(c.b)};
}

void runStrip(const StripOptions& o) {
    checkOutputName(o.output, {".json"});
    nlohmann::json grain = o.base.empty() ? nlohmann::json::object() : parseJsonFile(o.base);
    if (!grain.is_object()) throw InputError(o.base, "", "expected a grain file (a JSON object)");
    ColourStrip s = analyseColourStrip(readStrip(o.input), o.input);

    nlohmann::json& colour = grain["colour"];
    if (!colour.is_object()) colour = nlohmann::json::object();
    // The strip's own early and late wood: its heart/sap shift goes into the offsets, so the
    // mean of early and late is the strip's overall colour.
    colour["early_wood"] = rgb(s.earlyWood);
    colour["late_wood"] = rgb(s.lateWood);
    nlohmann::json profile = nlohmann::json::array();
    for (double e : s.lateWoodProfile) profile.push_back(std::round(e * 1e3) / 1e3);
    colour["late_wood_profile"] = profile;
    colour["heartwood"] = {{"enabled", true},
                           {"start", std::max(0.0, s.heartwoodEnd - 2)},
                           {"end", s.heartwoodEnd + 2},
                           {"heartwood_offset", rgb(s.heartwoodOffset)},
                           {"sapwood_offset", rgb(s.sapwoodOffset)}};
    grain["reference"] = {{"strip", o.input},
                          {"rings", s.rings},
                          {"ring_width_cv", s.widthStatistics.cv},
                          {"ring_width_autocorrelation", s.widthStatistics.autocorrelation},
                          {"early_wood_lab", {s.early.L, s.early.a, s.early.b}},
                          {"late_wood_lab", {s.late.L, s.late.a, s.late.b}}};
    parseGrain(grain, o.output);  // a valid grain file, or the error says why

    writeTextAtomically(o.output, grain.dump(2) + '\n', "grain file");
    fmt::print(
        "{}: {} rings (width CV {:.2f}, lag-1 autocorrelation {:.2f}); early wood "
        "L*a*b* {:.1f}/{:.1f}/{:.1f}, late wood {:.1f}/{:.1f}/{:.1f}\nwrote {}\n",
        o.input, s.rings, s.widthStatistics.cv, s.widthStatistics.autocorrelation, s.early.L,
        s.early.a, s.early.b, s.late.L, s.late.a, s.late.b, o.output);
}

}  // namespace

void addGrainCommands(CLI::App& app) {
    CLI::App* grain = app.add_subcommand("grain", "Grain files: colours from a photograph");
    grain->require_subcommand(1);
    auto o = std::make_shared<StripOptions>();
    CLI::App* strip = grain->add_subcommand(
        "strip",
        "Measure a photographed strip (pith left, bark right) and write its ring colours, "
        "transition profile and heart/sapwood shift as grain colour keys");
    strip->add_option("photo", o->input, "The strip: PNG, BMP, JPEG (sRGB) or EXR (linear)")
        ->required();
    strip->add_option("-o,--output", o->output, "Output grain file (.json)")->required();
    strip->add_option("--grain", o->base,
                      "Grain file to start from (its other keys are kept; default: none)");
    strip->callback([o] { runStrip(*o); });
}

}  // namespace nenrin
