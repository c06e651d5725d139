#include "renderer/farm/part_merge.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "renderer/bake/baked_grid.h"
#include "renderer/bake/grid_bake.h"
#include "renderer/bake/grid_writers.h"
#include "renderer/colour_management.h"
#include "renderer/film.h"
#include "renderer/path_tracer.h"
#include "util/atomic_output.h"
#include "util/input_error.h"
#include "util/memory_budget.h"

namespace nenrin {

namespace {

std::string required(const FloatExr& exr, const std::string& path, const std::string& key) {
    auto it = exr.metadata.find(key);
    if (it == exr.metadata.end())
        throw InputError(path, "nenrin:" + key,
                         "missing: not a part of a split job (made by --tile K/N)");
    return it->second;
}

/// A volume's W H D from its metadata.
std::array<int, 3> volumeResolution(const FloatExr& exr, const std::string& path) {
    std::istringstream in(required(exr, path, "volume_resolution"));
    std::array<int, 3> r{};
    if (!(in >> r[0] >> r[1] >> r[2]) || r[0] != exr.width || r[1] < 1 || r[2] < 2 ||
        static_cast<long long>(r[1]) * r[2] != exr.height)
        throw InputError(
            path, "nenrin:volume_resolution",
            fmt::format("expected \"W H D\" matching the {}x{} atlas", exr.width, exr.height));
    return r;
}

/// The rows part `number` of this job must hold.
RowBand expectedRows(JobKind kind, const FloatExr& exr, const std::string& path,
                     PartNumber number) {
    switch (kind) {
        case JobKind::Render:
            return bandOfPart(exr.height, kRenderTileSize, number.part, number.parts);
        case JobKind::BakeSlice:
            return bandOfPart(exr.height, bakeTileLayers(false), number.part, number.parts);
        case JobKind::BakeVolume: {
            const auto r = volumeResolution(exr, path);
            RowBand layers = bandOfPart(r[2], bakeTileLayers(true), number.part, number.parts);
            return {layers.begin * r[1], layers.end * r[1]};
        }
    }
    return {};
}

std::map<std::string, std::string> withoutPartKeys(std::map<std::string, std::string> m) {
    for (const std::string& key : partKeys()) m.erase(key);
    return m;
}

Vec3 parseVec3(const FloatExr& exr, const std::string& key) {
    std::istringstream in(required(exr, "merged job", key));
    Vec3 v;
    if (!(in >> v.x >> v.y >> v.z))
        throw InputError("merged job", "nenrin:" + key, "expected three numbers");
    return v;
}

BakedGrid gridOf(const MergedJob& job) {
    const FloatExr& image = job.image;
    if (image.channels != std::vector<std::string>(kBakeChannels.begin(), kBakeChannels.end()))
        throw InputError("merged job", "channels", "not the channels of a bake");
    BakedGrid grid;
    grid.width = image.width;
    grid.height = image.height;
    grid.metadata = image.metadata;
    if (job.kind == JobKind::BakeVolume) {
        const auto r = volumeResolution(image, "merged job");
        grid.height = r[1];
        grid.depth = r[2];
        // writeExr adds these again for a volume.
        grid.metadata.erase("volume_resolution");
        grid.metadata.erase("volume_layout");
    }
    grid.origin = parseVec3(image, "sample_origin");
    grid.stepX = parseVec3(image, "sample_step_x");
    grid.stepY = parseVec3(image, "sample_step_y");
    grid.stepZ = parseVec3(image, "sample_step_z");
    grid.data = image.pixels;
    return grid;
}

}  // namespace

MergedJob mergeParts(const std::vector<std::string>& paths) {
    if (paths.empty()) throw InputError("command line", "PARTS", "no part files given");
    MergedJob job;
    std::string first, hash;
    std::map<std::string, std::string> metadata;
    std::vector<std::string> owner;  // file of each part number, "" until seen
    for (const std::string& path : paths) {
        FloatExr exr = readFloatExr(path);
        const PartNumber number = parsePartNumber(required(exr, path, "part"), path, "nenrin:part");
        const JobKind kind = parseJobKind(required(exr, path, "job"), path);
        if (kind == JobKind::Render) {
            const bool adaptive = std::find(exr.channels.begin(), exr.channels.end(), "samples") !=
                                  exr.channels.end();
            orderChannels(exr, filmChannelNames(adaptive), path);
        } else {
            orderChannels(exr, {kBakeChannels.begin(), kBakeChannels.end()}, path);
        }
        const std::string partHash = required(exr, path, "job_hash");
        if (first.empty()) {
            first = path;
            hash = partHash;
            job.kind = kind;
            job.parts = number.parts;
            if (double(exr.width) * exr.height * exr.channels.size() > double(1u << 30))
                throw InputError(path, "data window",
                                 fmt::format("a {}x{} frame of {} channels: over the limit of "
                                             "2^30 values",
                                             exr.width, exr.height, exr.channels.size()));
            // The merged frame, the part being read and the writer's copy.
            requireMemory(3.0 * 4 * exr.width * exr.height * exr.channels.size(),
                          fmt::format("merging a {}x{} frame of {} channels", exr.width, exr.height,
                                      exr.channels.size()),
                          path);
            owner.assign(number.parts, "");
            metadata = withoutPartKeys(exr.metadata);
            job.image.width = exr.width;
            job.image.height = exr.height;
            job.image.channels = exr.channels;
            job.image.pixels.assign(size_t(exr.width) * exr.height * exr.channels.size(), 0.f);
        } else if (partHash != hash || kind != job.kind || number.parts != job.parts ||
                   exr.width != job.image.width || exr.height != job.image.height ||
                   exr.channels != job.image.channels ||
                   withoutPartKeys(exr.metadata) != metadata) {
            throw InputError(
                path, "nenrin:job_hash",
                fmt::format("belongs to another job than {} ({} {}x{} in {} parts, fingerprint "
                            "{}; this is {} {}x{} in {} parts, fingerprint {}): parts of "
                            "different scenes, settings or input files do not merge",
                            first, jobKindName(job.kind), job.image.width, job.image.height,
                            job.parts, hash, jobKindName(kind), exr.width, exr.height, number.parts,
                            partHash));
        }
        std::string& seen = owner[number.part - 1];
        if (!seen.empty())
            throw InputError(path, "nenrin:part",
                             fmt::format("part {}/{} twice: {} is that part too", number.part,
                                         number.parts, seen));
        seen = path;
        const RowBand rows = expectedRows(kind, exr, path, number);
        if (exr.band.begin != rows.begin || exr.band.end != rows.end)
            throw InputError(path, "data window",
                             fmt::format("holds rows {}..{}, but part {}/{} of this job is rows "
                                         "{}..{} (a damaged or altered file?)",
                                         exr.band.begin, exr.band.end - 1, number.part,
                                         number.parts, rows.begin, rows.end - 1));
        const size_t channels = exr.channels.size();
        for (size_t i = 0; i < exr.pixels.size(); ++i)
            if (!std::isfinite(exr.pixels[i])) {
                const size_t pixel = i / channels;
                throw InputError(path, "pixels",
                                 fmt::format("pixel ({}, {}) channel {} is {}: a part must hold "
                                             "finite numbers only",
                                             pixel % exr.width, rows.begin + pixel / exr.width,
                                             exr.channels[i % channels], exr.pixels[i]));
            }
        std::copy(exr.pixels.begin(), exr.pixels.end(),
                  job.image.pixels.begin() + size_t(rows.begin) * exr.width * channels);
    }
    std::string missing;
    for (int k = 1; k <= job.parts; ++k)
        if (owner[k - 1].empty()) {
            job.image.metadata = metadata;
            RowBand rows = expectedRows(job.kind, job.image, first, {k, job.parts});
            missing += fmt::format("{}{}/{} (rows {}..{})", missing.empty() ? "" : ", ", k,
                                   job.parts, rows.begin, rows.end - 1);
        }
    if (!missing.empty())
        throw InputError(
            "merge", "",
            fmt::format("missing part{} {} of the job of {}: nothing written",
                        missing.find(',') == std::string::npos ? "" : "s", missing, first));
    job.image.metadata = std::move(metadata);
    return job;
}

void checkMergeOutputs(const std::string& output, const std::string& png) {
    checkOutputName(output, {".exr", ".vdb", ".df3"});
    if (!png.empty()) checkOutputName(png, {".png"});
}

std::vector<std::string> writeMergedJob(const MergedJob& job, const std::string& output,
                                        const std::string& png) {
    const std::string ext = lowerExtension(output);
    if (job.kind != JobKind::BakeVolume && ext != ".exr")
        throw InputError(output, "", fmt::format("a {} is written as .exr", jobKindName(job.kind)));
    if (job.kind == JobKind::BakeVolume && !png.empty())
        throw InputError(png, "", "a volume has no PNG preview");
    if (job.kind == JobKind::Render) {
        Film film = filmFromExr(job.image, "merged job");
        writeFilmExr(film, output, job.image.metadata);
        std::vector<std::string> files{output};
        if (!png.empty()) {
            writePreviewPng(png, film.rgb, film.width, film.height);
            files.push_back(png);
        }
        return files;
    }
    BakedGrid grid = gridOf(job);
    if (job.kind == JobKind::BakeVolume) return writeVolume(grid, output);
    std::vector<std::string> files = writeExr(grid, output);
    if (!png.empty()) {
        writeSlicePreviewPng(grid, png);
        files.push_back(png);
    }
    return files;
}

}  // namespace nenrin
