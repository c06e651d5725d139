#include "denoise_command.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <memory>

#include "renderer/colour_management.h"
#include "renderer/denoise/atrous_denoiser.h"
#include "renderer/exr_file.h"
#include "renderer/film.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

struct DenoiseArguments {
    std::string input, output, png;
    DenoiseOptions options;
};

/// The render's spp (nenrin:spp), which tells the visibility AOV's noise; 0 if the header has
/// none (a note says so), an InputError if it is not a count.
double samplesPerPixel(const FloatExr& image, const std::string& path) {
    const auto spp = image.metadata.find("spp");
    if (spp == image.metadata.end()) {
        fmt::print("{} has no nenrin:spp: the visibility AOV's noise is not allowed for\n", path);
        return 0;
    }
    const std::string& text = spp->second;
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value < 1)
        throw InputError(path, "nenrin:spp", "a sample count, found \"" + text + "\"");
    return value;
}

/// Appends channel `name` to every pixel, its value made from the pixel's others.
template <class ValueOf>
void appendChannel(FloatExr& image, const std::string& name, ValueOf valueOf) {
    const size_t n = image.channels.size();
    std::vector<float> pixels;
    pixels.reserve(image.pixels.size() / n * (n + 1));
    for (size_t i = 0; i + n <= image.pixels.size(); i += n) {
        pixels.insert(pixels.end(), image.pixels.begin() + i, image.pixels.begin() + i + n);
        pixels.push_back(valueOf(&image.pixels[i]));
    }
    image.pixels = std::move(pixels);
    image.channels.push_back(name);
}

/// A render from before the visibility, occlusion or diffuse AOVs: visibility added as 1
/// everywhere (no shadow edge to guide by), occlusion as 0 (no corner), diffuse as all of R, G,
/// B (gloss divided by the albedo as the rest is), each with a note. Whether anything else is
/// missing orderChannels says.
void addAovsIfMissing(FloatExr& image, const std::string& path) {
    const auto& c = image.channels;
    auto has = [&](const std::string& name) {
        return std::find(c.begin(), c.end(), name) != c.end();
    };
    if (!has("variance") || !has("R") || !has("G") || !has("B")) return;
    auto note = [&](const char* aov, const char* consequence) {
        fmt::print("{} has no {} AOV (rendered by an older nenrin): {}\n", path, aov, consequence);
    };
    if (!has("visibility")) {
        appendChannel(image, "visibility", [](const float*) { return 1.0f; });
        note("visibility", "shadow edges are not guided");
    }
    if (!has("occlusion")) {
        appendChannel(image, "occlusion", [](const float*) { return 0.0f; });
        note("occlusion", "corners are not guided");
    }
    if (!has("diffuse.R")) {
        for (const char* channel : {"R", "G", "B"}) {
            const size_t k = size_t(std::find(c.begin(), c.end(), channel) - c.begin());
            appendChannel(image, std::string("diffuse.") + channel,
                          [k](const float* pixel) { return pixel[k]; });
        }
        note("diffuse", "gloss is filtered with the diffuse light");
    }
}

void runDenoise(const DenoiseArguments& a) {
    checkOutputName(a.output, {".exr"});
    if (!a.png.empty()) checkOutputName(a.png, {".png"});
    FloatExr image = readFloatExr(a.input);
    const bool adaptive =
        std::find(image.channels.begin(), image.channels.end(), "samples") != image.channels.end();
    addAovsIfMissing(image, a.input);
    orderChannels(image, filmChannelNames(adaptive), a.input);
    if (image.band.begin != 0 || (image.band.end != -1 && image.band.end != image.height))
        throw InputError(a.input, "data window",
                         "a part of a split render: merge the parts first (nenrin merge)");
    Film film = filmFromExr(image, a.input);
    if (image.metadata.count("denoised"))
        throw InputError(a.input, "nenrin:denoised", "the image is denoised already");
    DenoiseOptions options = a.options;
    options.samples = samplesPerPixel(image, a.input);
    const auto start = std::chrono::steady_clock::now();
    denoiseFilm(film, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::map<std::string, std::string> metadata = image.metadata;
    metadata["denoised"] = denoiseDescription(options);
    writeFilmExr(film, a.output, metadata, a.options.threads);
    fmt::print("wrote {}\n", a.output);
    if (!a.png.empty()) {
        writePreviewPng(a.png, film.rgb, film.width, film.height);
        fmt::print("wrote {} ({})\n", a.png, displayConfigName());
    }
    fmt::print("{}x{} denoised in {:.2f} s\n", film.width, film.height, seconds);
}

}  // namespace

void addDenoiseCommand(CLI::App& app) {
    auto a = std::make_shared<DenoiseArguments>();
    CLI::App* cmd = app.add_subcommand(
        "denoise",
        "Denoise a rendered EXR (nenrin render's channels, a split render merged): the "
        "edge-avoiding a-trous filter guided by its albedo, normal, depth, visibility, "
        "occlusion and variance AOVs, diffuse light and gloss apart; the grain, which lives in "
        "the albedo, is kept (docs/denoise.md)");
    cmd->add_option("input", a->input, "A nenrin render EXR")->required();
    cmd->add_option("-o,--output", a->output, "The denoised EXR (the same channels)")->required();
    cmd->add_option("--png", a->png, "Also write an 8-bit sRGB preview through OpenColorIO");
    cmd->add_option("--passes", a->options.passes, "Filter passes (each doubles the reach)")
        ->check(CLI::Range(1, 12))
        ->default_val(a->options.passes);
    cmd->add_option("--sigma-luminance", a->options.sigmaLuminance,
                    "Luminance differences smoothed, in standard deviations of the pixel's noise")
        ->check(CLI::Range(0.1, 100.0))
        ->default_val(a->options.sigmaLuminance);
    cmd->add_option("--normal-exponent", a->options.normalExponent,
                    "Normal weight: cos(angle between the normals) to this power")
        ->check(CLI::Range(0.0, 10000.0))
        ->default_val(a->options.normalExponent);
    cmd->add_option("--sigma-depth", a->options.sigmaDepth,
                    "Depth differences smoothed, in units of the depth's slope over the distance")
        ->check(CLI::Range(0.01, 100.0))
        ->default_val(a->options.sigmaDepth);
    cmd->add_option("--sigma-visibility", a->options.sigmaVisibility,
                    "Differences in the share of the first hit's direct light not blocked "
                    "(shadow edges) smoothed")
        ->check(CLI::Range(0.001, 100.0))
        ->default_val(a->options.sigmaVisibility);
    cmd->add_option("--sigma-occlusion", a->options.sigmaOcclusion,
                    "Differences in how near the first bounce found geometry (the darkening "
                    "into corners) smoothed")
        ->check(CLI::Range(0.001, 100.0))
        ->default_val(a->options.sigmaOcclusion);
    cmd->add_option("--sigma-albedo", a->options.sigmaAlbedo,
                    "Albedo differences smoothed, relative to the pixel's albedo (boards, knots "
                    "and rings under a glossy finish, in renders without the diffuse AOV)")
        ->check(CLI::Range(0.001, 100.0))
        ->default_val(a->options.sigmaAlbedo);
    cmd->add_option("--threads", a->options.threads, "Worker threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->default_val(0);
    cmd->callback([a] { runDenoise(*a); });
}

}  // namespace nenrin
