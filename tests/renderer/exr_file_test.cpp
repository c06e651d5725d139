// renderer/exr_file: an EXR written with its blocks compressed on several threads is the same
// file, byte for byte, as one written on one thread, and reads back as written; channels
// written from separate planes make the same file as the same values interleaved; blocks our
// ZIP encoder (renderer/exr_zip) cannot shrink are stored raw, and OpenEXR reads both kinds.

#include "renderer/exr_file.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "renderer/exr_zip.h"
#include "renderer/film.h"
#include "tests/scratch_path.h"
#include "util/hash.h"

namespace nenrin {
namespace {

std::string fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ExrFile, ThreadsCompressTheSameBytes) {
    // 300 rows: 19 blocks of 16, the last one short; values that compress a little.
    const int width = 97, height = 300;
    std::vector<float> pixels(size_t(width) * height * 2);
    for (size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = float(i % 7 == 0 ? uniform01(3, i) : double(i % 300) / 300);
    std::vector<std::string> files;
    for (int threads : {1, 2, 4}) {
        const auto path = scratchPath("exr-threads-" + std::to_string(threads) + ".exr");
        writeFloatExr(path.string(), path.string(), width, height, {"R", "Z"}, pixels.data(),
                      {{"k", "v"}}, {}, ExrValues::SceneLinear, threads);
        files.push_back(fileBytes(path));
        if (threads == 4) {
            const FloatExr back = readFloatExr(path.string());
            ASSERT_EQ(back.pixels.size(), pixels.size());
            EXPECT_EQ(back.pixels, pixels);
        }
        std::filesystem::remove(path);
    }
    ASSERT_GT(files[0].size(), 1000u);
    EXPECT_EQ(files[1], files[0]);
    EXPECT_EQ(files[2], files[0]);
}

TEST(FilmExr, EveryChannelComesBackFromItsOwnPlane) {
    // Each plane of a film filled with values of its own: written and read back, each must
    // land in the plane it came from, under its name (the channel list and the planes are
    // stated apart; a channel added to one and not the other shifts or loses the rest).
    for (const bool adaptive : {false, true}) {
        Film film;
        film.resize(7, 5);
        if (adaptive) film.samples.assign(film.alpha.size(), 0);
        std::vector<FilmPlane*> planes = {&film.rgb,        &film.albedo,     &film.normal,
                                          &film.diffuse,    &film.alpha,      &film.depth,
                                          &film.growthTime, &film.knot,       &film.lamella,
                                          &film.variance,   &film.visibility, &film.occlusion};
        if (adaptive) planes.push_back(&film.samples);
        for (size_t k = 0; k < planes.size(); ++k)
            for (size_t i = 0; i < planes[k]->size(); ++i) (*planes[k])[i] = float(100 * k + i);
        const auto path = scratchPath("film-planes.exr");
        writeFilmExr(film, path.string(), {});
        FloatExr image = readFloatExr(path.string());
        std::filesystem::remove(path);
        orderChannels(image, filmChannelNames(adaptive), path.string());  // EXR sorts them
        const Film back = filmFromExr(image, path.string());
        const std::vector<const FilmPlane*> backPlanes = {
            &back.rgb,        &back.albedo,     &back.normal, &back.diffuse, &back.alpha,
            &back.depth,      &back.growthTime, &back.knot,   &back.lamella, &back.variance,
            &back.visibility, &back.occlusion,  &back.samples};
        for (size_t k = 0; k < planes.size(); ++k) EXPECT_EQ(*backPlanes[k], *planes[k]) << k;
    }
}

TEST(ExrFile, ChannelsApartInMemoryWriteTheSameFileAsInterleaved) {
    // A film's layout: R, G, B interleaved in one plane, Z in another; a band of rows 5..44.
    const int width = 31, height = 60, first = 5, rows = 40;
    const size_t n = size_t(width) * rows;
    std::vector<float> rgb(3 * n), z(n), interleaved(4 * n);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) rgb[3 * i + c] = float(uniform01(c, i));
        z[i] = float(i % 97) * 0.25f;
        for (int c = 0; c < 3; ++c) interleaved[4 * i + c] = rgb[3 * i + c];
        interleaved[4 * i + 3] = z[i];
    }
    const auto a = scratchPath("exr-interleaved.exr"), b = scratchPath("exr-planes.exr");
    const RowBand band{first, first + rows};
    writeFloatExr(a.string(), a.string(), width, height, {"R", "G", "B", "Z"}, interleaved.data(),
                  {}, band);
    writeFloatExrChannels(b.string(), b.string(), width, height,
                          {{"R", rgb.data(), 3},
                           {"G", rgb.data() + 1, 3},
                           {"B", rgb.data() + 2, 3},
                           {"Z", z.data(), 1}},
                          {}, band);
    EXPECT_EQ(fileBytes(b), fileBytes(a));
    EXPECT_GT(fileBytes(a).size(), 1000u);
    // A non-finite value in a plane is named by its pixel and channel, and nothing is written.
    std::filesystem::remove(b);
    rgb[3 * (2 * width + 7) + 1] = std::numeric_limits<float>::infinity();
    try {
        writeFloatExrChannels(b.string(), b.string(), width, height,
                              {{"R", rgb.data(), 3}, {"G", rgb.data() + 1, 3}}, {}, band);
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("sample (7, 7), channel G is inf"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(b));
    std::filesystem::remove(a);
}

TEST(ExrFile, WhatOpenExrRejectsIsAnErrorAndLongKeysAreKept) {
    // OpenEXRCore reports a bad header while it holds its context's lock: the error must come
    // back as an InputError naming the file (an error callback that asked the context for its
    // user data deadlocked here).
    const auto path = scratchPath("exr-rejected.exr");
    const std::vector<float> pixels(2 * 4 * 3, 0.5f);
    for (const auto& [width, channels] :
         {std::pair<int, std::vector<std::string>>{4, {"R", "R"}}, {0, {"R", "G"}}}) {
        try {
            writeFloatExr(path.string(), path.string(), width, 3, channels, pixels.data(), {});
            ADD_FAILURE() << "no error for width " << width;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
        }
    }
    // A metadata name over 31 characters needs OpenEXR's long-name flag.
    const std::string key(40, 'k');
    writeFloatExr(path.string(), path.string(), 4, 3, {"R", "G"}, pixels.data(), {{key, "v"}});
    EXPECT_EQ(readFloatExr(path.string()).metadata.at(key), "v");
    std::filesystem::remove(path);
}

TEST(ExrZip, KeepsWhatDoesNotShrinkAndShrinksWhatRepeats) {
    ExrZipCompressor zip;
    std::vector<uint8_t> noise(4096), smooth(4096);
    for (size_t i = 0; i < noise.size(); ++i) {
        noise[i] = static_cast<uint8_t>(uniform01(5, i) * 256);
        smooth[i] = static_cast<uint8_t>(i / 64);
    }
    const auto kept = zip.compress(noise);
    EXPECT_EQ(kept.data(), noise.data());
    EXPECT_EQ(kept.size(), noise.size());
    const auto shrunk = zip.compress(smooth);
    EXPECT_NE(shrunk.data(), smooth.data());
    EXPECT_LT(shrunk.size(), smooth.size() / 10);
}

TEST(ExrFile, BlocksThatDoNotCompressAreStoredRawAndReadBack) {
    // Rows 0..15 (the first block) random bit patterns of finite floats: no compression shrinks
    // them, so the block is stored raw; rows 16..39 smooth, compressed. OpenEXR's own reader
    // (readFloatExr) must give back every bit of both.
    const int width = 64, height = 40;
    std::vector<float> pixels(size_t(width) * height);
    for (size_t i = 0; i < pixels.size(); ++i) {
        uint32_t bits = static_cast<uint32_t>(uniform01(9, i) * 0x1.0p32);
        if ((bits & 0x7F800000u) == 0x7F800000u) bits ^= 0x40000000u;  // not inf or NaN
        pixels[i] = i < size_t(16 * width) ? std::bit_cast<float>(bits) : float(i % width) / width;
    }
    const auto path = scratchPath("exr-raw-block.exr");
    writeFloatExr(path.string(), path.string(), width, height, {"Y"}, pixels.data(), {});
    const size_t bytes = fileBytes(path).size();
    const FloatExr back = readFloatExr(path.string());
    std::filesystem::remove(path);
    // The raw block is all of its 4 KB; the smooth rows add little.
    EXPECT_GT(bytes, size_t(16 * width * 4));
    EXPECT_LT(bytes, size_t(16 * width * 4) + 2000);
    ASSERT_EQ(back.pixels.size(), pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
        ASSERT_EQ(std::bit_cast<uint32_t>(back.pixels[i]), std::bit_cast<uint32_t>(pixels[i])) << i;
}

}  // namespace
}  // namespace nenrin
