#include "compare_command.h"

#include <fmt/format.h>

#include <cmath>

#include "arguments.h"
#include "renderer/exr_file.h"
#include "renderer/image_error/flip.h"
#include "renderer/image_file.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

struct CompareOptions {
    std::string a, b, diff;
    double threshold = 0.02;  ///< per-value error counted as "over"
    double maxRmse = -1, minPsnr = -1, maxMean = -1, maxOverPercent = -1;
    bool flip = false;
    std::string flipMap, flipMode = "auto";
    double ppd = kFlipDefaultPpd, maxFlip = -1;
};

/// R, G, B of an image, 3 floats per pixel; every value must be finite.
ImageFile readRgb(const std::string& path) {
    ImageFile image = readImageFile(path);
    if (image.channels < 3) throw InputError(path, "", "expected at least R, G, B channels");
    std::vector<float> rgb(size_t(image.width) * image.height * 3);
    for (size_t i = 0; i < rgb.size() / 3; ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = image.pixels[i * image.channels + c];
            if (!std::isfinite(v))
                throw InputError(path,
                                 fmt::format("pixel ({}, {})", i % image.width, i / image.width),
                                 fmt::format("channel {} is {}: expected a finite value",
                                             image.channelNames[c], v));
            rgb[i * 3 + c] = v;
        }
    image.pixels = std::move(rgb);
    image.channels = 3;
    return image;
}

/// FLIP of B against A (the reference): prints the mean and its mode, writes the map if asked.
double flip(const CompareOptions& o, const ImageFile& a, const ImageFile& b) {
    const bool hdr = o.flipMode == "hdr" || (o.flipMode == "auto" && a.floatingPoint);
    const FlipImage reference{a.width, a.height, a.pixels}, test{b.width, b.height, b.pixels};
    std::vector<float> error;
    std::string how;
    if (hdr) {
        const FlipExposures e = flipExposures(reference);
        error = hdrFlip(reference, test, e, o.ppd);
        how = fmt::format("HDR: {} exposures, {:+.2f} to {:+.2f} stops", e.count, e.start, e.stop);
    } else {
        error = ldrFlip(reference, test, o.ppd);
        how = "LDR: values as sRGB";
    }
    double sum = 0;
    for (float e : error) sum += e;
    const double mean = sum / double(error.size());
    fmt::print("FLIP mean {:.6g}  ({}; {:.1f} pixels per degree)\n", mean, how, o.ppd);
    if (!o.flipMap.empty()) {
        // The error as grey (R = G = B), linear: 1 is white.
        std::vector<float> grey(3 * error.size());
        for (size_t i = 0; i < error.size(); ++i)
            grey[3 * i] = grey[3 * i + 1] = grey[3 * i + 2] = error[i];
        AtomicOutput out(o.flipMap);
        writeFloatExr(o.flipMap, out.temporaryPath(), a.width, a.height, {"R", "G", "B"},
                      grey.data(),
                      {{"flip:mean", fmt::format("{:.9g}", mean)}, {"flip:mode", how}});
        out.commit();
        fmt::print("wrote {}\n", o.flipMap);
    }
    return mean;
}

int compare(const CompareOptions& o) {
    if (!o.diff.empty()) checkOutputName(o.diff, {".exr"});
    if (!o.flipMap.empty()) checkOutputName(o.flipMap, {".exr"});
    const ImageFile a = readRgb(o.a), b = readRgb(o.b);
    if (a.width != b.width || a.height != b.height)
        throw InputError(
            o.b, "",
            fmt::format("is {}x{}, but {} is {}x{}", b.width, b.height, o.a, a.width, a.height));
    // Over all R, G, B values: RMSE, PSNR (peak 1), mean and largest absolute error, and the
    // share of values whose error is over the threshold.
    struct {
        double rms_error = 0, PSNR = 0, meanerror = 0, maxerror = 0;
        int maxx = 0, maxy = 0;
        size_t nfail = 0;
    } r;
    std::vector<float> difference(a.pixels.size());
    double squares = 0, sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const double d = std::abs(double(a.pixels[i]) - double(b.pixels[i]));
        difference[i] = static_cast<float>(d);
        squares += d * d;
        sum += d;
        r.nfail += d > o.threshold;
        if (d > r.maxerror) {
            r.maxerror = d;
            r.maxx = static_cast<int>((i / 3) % a.width);
            r.maxy = static_cast<int>((i / 3) / a.width);
        }
    }
    const double values = double(a.pixels.size());
    r.rms_error = std::sqrt(squares / values);
    r.meanerror = sum / values;
    r.PSNR = r.rms_error > 0 ? 20 * std::log10(1 / r.rms_error) : INFINITY;
    double overPercent = 100.0 * r.nfail / values;
    fmt::print(
        "RMSE {:.6g}  PSNR {:.2f} dB  mean abs error {:.6g}  max abs error {:.6g} at "
        "({}, {})  over {}: {:.3f}% of values\n",
        r.rms_error, r.PSNR, r.meanerror, r.maxerror, r.maxx, r.maxy, o.threshold, overPercent);
    if (!o.diff.empty()) {
        AtomicOutput out(o.diff);
        writeFloatExr(o.diff, out.temporaryPath(), a.width, a.height, {"R", "G", "B"},
                      difference.data(), {});
        out.commit();
        fmt::print("wrote {}\n", o.diff);
    }
    std::vector<std::string> failures;
    if (o.flip || !o.flipMap.empty() || o.maxFlip >= 0) {
        const double mean = flip(o, a, b);
        if (o.maxFlip >= 0 && mean > o.maxFlip)
            failures.push_back(fmt::format("FLIP {:.6g} > {}", mean, o.maxFlip));
    }
    if (o.maxRmse >= 0 && r.rms_error > o.maxRmse)
        failures.push_back(fmt::format("RMSE {:.6g} > {}", r.rms_error, o.maxRmse));
    if (o.minPsnr >= 0 && r.PSNR < o.minPsnr)
        failures.push_back(fmt::format("PSNR {:.2f} < {}", r.PSNR, o.minPsnr));
    if (o.maxMean >= 0 && r.meanerror > o.maxMean)
        failures.push_back(fmt::format("mean error {:.6g} > {}", r.meanerror, o.maxMean));
    if (o.maxOverPercent >= 0 && overPercent > o.maxOverPercent)
        failures.push_back(
            fmt::format("{:.3f}% over {} > {}%", overPercent, o.threshold, o.maxOverPercent));
    for (const auto& f : failures) fmt::print(stderr, "nenrin: compare: {}\n", f);
    return failures.empty() ? 0 : 2;
}

}  // namespace

void addCompareCommand(CLI::App& app) {
    auto c = std::make_shared<CompareOptions>();
    CLI::App* cmp =
        app.add_subcommand("compare",
                           "Compare the RGB of two images (OpenImageIO): RMSE, PSNR, mean and max "
                           "absolute error, share of values over --threshold, and with --flip the "
                           "perceptual FLIP error of B against A; exit 2 past a limit "
                           "(docs/compare.md)");
    cmp->add_option("a", c->a, "First image")->required();
    cmp->add_option("b", c->b, "Second image")->required();
    cmp->add_option("--diff", c->diff, "Write |A - B| as an EXR");
    cmp->add_option("--threshold", c->threshold, "Per-value error counted as over")
        ->check(finiteRange(0, 1e30))
        ->default_val(0.02);
    cmp->add_option("--max-rmse", c->maxRmse, "Fail if the RMSE is larger")
        ->check(finiteRange(0, 1e30));
    cmp->add_option("--min-psnr", c->minPsnr, "Fail if the PSNR (dB) is smaller")
        ->check(finiteRange(0, 1e3));
    cmp->add_option("--max-mean", c->maxMean, "Fail if the mean absolute error is larger")
        ->check(finiteRange(0, 1e30));
    cmp->add_option("--max-over-percent", c->maxOverPercent,
                    "Fail if more than this % of values are over --threshold")
        ->check(finiteRange(0, 100));
    cmp->add_flag("--flip", c->flip,
                  "Also the FLIP error of B against the reference A (mean over the pixels)");
    cmp->add_option("--flip-map", c->flipMap, "Write the per-pixel FLIP error as a grey EXR");
    cmp->add_option("--flip-mode", c->flipMode,
                    "hdr (linear images, tone-mapped at several exposures), ldr (values taken "
                    "as sRGB in [0, 1]) or auto: hdr when A is a float image (EXR, HDR)")
        ->check(CLI::IsMember({"auto", "ldr", "hdr"}))
        ->default_val("auto");
    cmp->add_option("--ppd", c->ppd,
                    "The viewer's pixels per degree (default: 0.7 m from a 0.7 m wide 4K screen)")
        ->check(finiteRange(1, 1000))
        ->default_val(kFlipDefaultPpd);
    cmp->add_option("--max-flip", c->maxFlip, "Fail if the mean FLIP error is larger")
        ->check(finiteRange(0, 1));
    cmp->callback([c] {
        int code = compare(*c);
        if (code != 0) {
            commitOutputs();  // the difference image is the report of a failed comparison
            throw CLI::RuntimeError(code);
        }
    });
}

}  // namespace nenrin
