#include "renderer/film.h"

#include <stdexcept>

#include "renderer/exr_file.h"
#include "renderer/parallel_tiles.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

void Film::resize(int w, int h, int first, int count) {
    width = w;
    height = h;
    firstRow = first;
    rows = count < 0 ? h - first : count;
    size_t n = size_t(w) * rows;
    // New planes, not assign(): their zeros are the fresh pages' own, and the tiles that write
    // them take the pages' first touches in parallel.
    for (FilmPlane* p : {&rgb, &albedo, &normal, &diffuse}) *p = FilmPlane(3 * n);
    for (FilmPlane* p : {&alpha, &depth, &growthTime, &knot, &variance, &occlusion})
        *p = FilmPlane(n);
    lamella.assign(n, -1);
    visibility.assign(n, 1);
}

std::vector<std::string> filmChannelNames(bool adaptive) {
    std::vector<std::string> names = {
        "R",        "G",          "B",         "A",         "albedo.R",  "albedo.G", "albedo.B",
        "N.X",      "N.Y",        "N.Z",       "Z",         "T",         "knot",     "lamella",
        "variance", "visibility", "occlusion", "diffuse.R", "diffuse.G", "diffuse.B"};
    if (adaptive) names.push_back("samples");
    return names;
}

std::string filmChannelDescription(bool adaptive) {
    std::string text =
        "R,G,B: scene-linear radiance; A: coverage; albedo; N: world normal; Z: depth along "
        "the view axis (m); T: growth time (years); knot: 0..1; lamella: board id or -1; "
        "variance: of the pixel's mean luminance; visibility: share of the first hit's direct "
        "light not blocked; occlusion: how near the first bounce found geometry (0..1); diffuse: "
        "the part of R,G,B the first hit's albedo carries";
    if (adaptive) text += "; samples: samples the pixel took";
    return text;
}

namespace {

/// Where each channel of filmChannelNames(true) lives in a film: its first value and the step
/// to the next pixel's. The one statement of the channel layout, for reading and writing.
template <class F>
auto filmPlanes(F& film) {
    using Pointer = decltype(film.rgb.data());
    struct Plane {
        Pointer values;
        size_t stride;
    };
    return std::vector<Plane>{
        {film.rgb.data(), 3},         {film.rgb.data() + 1, 3},     {film.rgb.data() + 2, 3},
        {film.alpha.data(), 1},       {film.albedo.data(), 3},      {film.albedo.data() + 1, 3},
        {film.albedo.data() + 2, 3},  {film.normal.data(), 3},      {film.normal.data() + 1, 3},
        {film.normal.data() + 2, 3},  {film.depth.data(), 1},       {film.growthTime.data(), 1},
        {film.knot.data(), 1},        {film.lamella.data(), 1},     {film.variance.data(), 1},
        {film.visibility.data(), 1},  {film.occlusion.data(), 1},   {film.diffuse.data(), 3},
        {film.diffuse.data() + 1, 3}, {film.diffuse.data() + 2, 3}, {film.samples.data(), 1}};
}

/// The planes of `film`, one per channel of filmChannelNames(true): the two lists are stated
/// apart, and a channel added to one alone would shift every later one.
template <class F>
auto checkedPlanes(F& film) {
    auto planes = filmPlanes(film);
    if (planes.size() != filmChannelNames(true).size())
        throw std::logic_error("film: channel names and planes differ in number");
    return planes;
}

}  // namespace

Film filmFromExr(const FloatExr& image, const std::string& file) {
    Film film;
    film.resize(image.width, image.height);
    const size_t channels = image.channels.size();
    const bool adaptive = channels == filmChannelNames(true).size();
    if (image.channels != filmChannelNames(adaptive))
        throw InputError(file, "channels",
                         "not the channels of a nenrin render (docs/render.md#outputs)");
    if (adaptive) film.samples.assign(film.alpha.size(), 0);
    const auto planes = checkedPlanes(film);
    for (size_t c = 0; c < channels; ++c)
        for (size_t i = 0; i < film.alpha.size(); ++i)
            planes[c].values[i * planes[c].stride] = image.pixels[i * channels + c];
    return film;
}

void writeFilmExr(const Film& film, const std::string& path,
                  const std::map<std::string, std::string>& metadata, int threads) {
    // Straight from the film's planes: an interleaved copy of a 4K frame's 16 channels would
    // be another half gigabyte.
    const std::vector<std::string> names = filmChannelNames(!film.samples.empty());
    const auto planes = checkedPlanes(film);
    std::vector<ExrChannel> channels;
    for (size_t c = 0; c < names.size(); ++c)
        channels.push_back({names[c], planes[c].values, planes[c].stride});
    AtomicOutput out(path);
    writeFloatExrChannels(path, out.temporaryPath(), film.width, film.height, channels, metadata,
                          {film.firstRow, film.firstRow + film.rows}, ExrValues::SceneLinear,
                          workerThreads(threads));
    out.commit();
}

}  // namespace nenrin
