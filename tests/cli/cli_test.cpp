// End-to-end tests of the nenrin command: every bad input ends in one error line that names the
// file and the place (JSON path, line:column or option), a non-zero exit code and no output
// file (nor a temporary `.NAME.partial-PID.ext`) left behind; good bakes write what the format
// documentation promises, and the result does not depend on the number of threads.
//
// Each test runs the binary (NENRIN_BINARY) in its own fresh temporary directory, with every
// path absolute, so nothing depends on the working directory of the test runner.

#include <regex>

#include "tests/cli/cli_fixture.h"

namespace {

// ---------------------------------------------------------------------------------------------
// Bad JSON files

TEST_F(CliTest, MalformedJsonNamesLineAndColumn) {
    auto file = fixture("malformed.json");  // a '[' where a ',' belongs: line 3, column 35
    expectInputError(slice({{"--skeleton", file}}),
                     {file + ": line 3, column 35: ", "invalid JSON", "unexpected '['"});
}

// json_reader.cpp means to strip nlohmann's "[json.exception.parse_error.101] parse error at
// line L, column C: " prefix, but looks for "error: ", which that text never holds: the message
// repeats the library's exception name and the position.
TEST_F(CliTest, MalformedJsonMessageHasNoLibraryPrefix) {
    auto file = fixture("malformed.json");
    auto r = slice({{"--skeleton", file}});
    expectInputError(r, {file + ": line 3, column 35: "});
    EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
    EXPECT_EQ(countOf(r.err, "line 3, column 35"), 1u) << r.err;
}

TEST_F(CliTest, TruncatedJsonIsReportedAsTruncated) {
    auto file = fixture("truncated.json");  // ends after "[[0, 0, 0]," on line 3
    expectInputError(slice({{"--skeleton", file}}),
                     {file + ": line 3, column 35: ", "unexpected end of file", "truncated"});
}

TEST_F(CliTest, TopLevelArrayIsRejected) {
    auto file = fixture("top-level-array.json");
    expectInputError(slice({{"--skeleton", file}}),
                     {file + ": (top level): ", "expected an object"});
}

TEST_F(CliTest, UnknownTopLevelKeyIsRejected) {
    auto file = fixture("unknown-top-level-key.json");
    expectInputError(slice({{"--skeleton", file}}), {file + ": trunks: ", "unknown key"});
}

TEST_F(CliTest, UnknownTrunkKeyIsRejected) {
    auto file = fixture("unknown-trunk-key.json");
    expectInputError(slice({{"--skeleton", file}}), {file + ": trunk.radius: ", "unknown key"});
}

TEST_F(CliTest, UnknownBranchKeyIsRejected) {
    auto file = fixture("unknown-branch-key.json");
    expectInputError(slice({{"--skeleton", file}}),
                     {file + ": branches[1].lenght: ", "unknown key"});
}

TEST_F(CliTest, UnknownNestedGrainKeyIsRejected) {
    auto file = fixture("unknown-grain-key.json");
    expectInputError(slice({{"--grain", file}}),
                     {file + ": colour.knots.darknening: ", "unknown key"});
}

TEST_F(CliTest, MissingTrunkIsRejected) {
    auto file = fixture("missing-trunk.json");
    expectInputError(slice({{"--skeleton", file}}), {file + ": trunk: ", "missing"});
}

TEST_F(CliTest, MissingTrunkPointsIsRejected) {
    auto file = fixture("missing-trunk-points.json");
    expectInputError(slice({{"--skeleton", file}}), {file + ": trunk.points: ", "missing"});
}

TEST_F(CliTest, NegativeElongationSpeedIsRejected) {
    auto file = fixture("negative-elongation-speed.json");
    expectInputError(
        slice({{"--skeleton", file}}),
        {file + ": elongation_speed: ", "expected at least 0.0001 (m/year", "found -1"});
}

TEST_F(CliTest, ZeroRadialSpeedIsRejected) {
    auto file = fixture("zero-radial-speed.json");
    expectInputError(slice({{"--grain", file}}),
                     {file + ": radial_speed: ", "expected at least 1e-05 (m/year"});
}

TEST_F(CliTest, NegativeBranchGammaIsRejected) {
    auto file = fixture("negative-branch-gamma.json");
    expectInputError(volume({{"--skeleton", file}}),
                     {file + ": branches[1].gamma: ", "expected at least 0.001", "found -0.5"});
}

// A number beyond double: nlohmann throws out_of_range (406), not parse_error; it must still be
// reported with the file and the number's line and column.
TEST_F(CliTest, OverflowingNumberInSkeletonNamesFileAndPlace) {
    auto file = fixture("overflow-number.json");  // "elongation_speed": 1e999 on line 2
    expectInputError(slice({{"--skeleton", file}}),
                     {file + ": line 2, column 23: ", "1e999", "finite"});
}

TEST_F(CliTest, OverflowingNumberInGrainNamesFileAndPlace) {
    auto file = fixture("overflow-grain-number.json");  // "felling_time": -1e999 on line 3
    expectInputError(slice({{"--grain", file}}),
                     {file + ": line 3, column 19: ", "1e999", "finite"});
}

// util/json_reader.cpp locates an overflowing number by searching the whole text for the token
// nlohmann names (text.find("1e999")), so the same characters earlier in the file (here in the
// description on line 2) give the wrong place: "line 2, column 27" instead of line 3, column 23.
TEST_F(CliTest, OverflowingNumberIsLocatedWhereItIsNotWhereItsTextFirstAppears) {
    auto file = fixture("overflow-number-text-seen-before.json");
    expectInputError(slice({{"--skeleton", file}}), {file + ": line 3, column 23: ", "1e999"});
}

TEST_F(CliTest, EmptyTrunkIsRejected) {
    auto file = fixture("empty-trunk.json");
    expectInputError(slice({{"--skeleton", file}}),
                     {file + ": trunk.points: ", "at least 2", "found 0"});
}

TEST_F(CliTest, OnePointTrunkIsRejected) {
    auto file = fixture("one-point-trunk.json");
    expectInputError(slice({{"--skeleton", file}}),
                     {file + ": trunk.points: ", "at least 2", "found 1"});
}

TEST_F(CliTest, BranchStartingOffTheTrunkIsRejected) {
    auto file = fixture("branch-off-trunk.json");  // start 0.5 m from the trunk's axis
    expectInputError(slice({{"--skeleton", file}}), {file + ": branches[0].start: ", "0.5 m off"});
}

TEST_F(CliTest, BranchAboveTheTrunkIsRejected) {
    auto file = fixture("branch-above-trunk.json");
    expectInputError(slice({{"--skeleton", file}}),
                     {file + ": branches[0].height: ", "off the trunk"});
}

TEST_F(CliTest, BranchBelowTheTrunkIsRejected) {
    auto file = fixture("branch-below-trunk.json");
    expectInputError(volume({{"--skeleton", file}}),
                     {file + ": branches[0].height: ", "off the trunk"});
}

TEST_F(CliTest, MissingSkeletonFileIsReported) {
    auto file = (in_ / "no-such-skeleton.json").string();
    expectInputError(slice({{"--skeleton", file}}), {file + ": ", "cannot open"});
}

TEST_F(CliTest, MissingGrainFileIsReported) {
    auto file = (in_ / "no-such-grain.json").string();
    expectInputError(volume({{"--grain", file}}), {file + ": ", "cannot open"});
}

TEST_F(CliTest, SubBranchWithHeightIsRejected) {
    // Generated input (not a fixture): a sub-branch placed by trunk "height".
    fs::path file = in_ / "sub-branch-height.json";
    std::ofstream(file) << R"({
  "trunk": { "points": [[0, 0, 0], [0, 0, 10]] },
  "branches": [
    { "height": 2, "azimuth": 0, "elevation": 30, "length": 1,
      "branches": [{ "height": 2.2, "azimuth": 90, "elevation": 0, "length": 0.2 }] }
  ]
}
)";
    expectInputError(slice({{"--skeleton", file.string()}}),
                     {file.string() + ": branches[0].branches[0].height: ", "\"at\""});
}

// ---------------------------------------------------------------------------------------------
// Bad command lines

TEST_F(CliTest, ZeroSizeBoxIsRejected) {
    expectInputError(volume({{"--box", "0,0,0,0,1,1"}}),
                     {"command line: --box: ", "zero-size or inverted", "0,0,0,0,1,1"});
}

TEST_F(CliTest, InvertedBoxIsRejected) {
    expectInputError(volume({{"--box", "1,1,1,0,0,0"}}),
                     {"command line: --box: ", "zero-size or inverted", "1,1,1,0,0,0"});
}

TEST_F(CliTest, BoxWithFiveNumbersIsRejected) {
    expectInputError(volume({{"--box", "0,0,0,1,1"}}),
                     {"command line: --box: ", "expected 6 comma-separated numbers"});
}

TEST_F(CliTest, SliceResolutionOverTheSideCapIsRejected) {
    expectInputError(slice({{"--res", "100000x100000"}}),
                     {"command line: --res: ", "16384", "100000x100000"});
}

TEST_F(CliTest, SliceResolutionOverThePixelCapIsRejected) {
    // Each side is allowed, their product is not.
    expectInputError(slice({{"--res", "16384x16384"}}),
                     {"command line: --res: ", "16384x16384", "over the cap"});
}

TEST_F(CliTest, MalformedSliceResolutionIsRejected) {
    expectInputError(slice({{"--res", "32"}}), {"command line: --res: ", "WIDTHxHEIGHT"});
}

TEST_F(CliTest, VolumeResolutionOverTheCapIsRejected) {
    expectInputError(volume({{"--res", "5000"}}), {"command line: --res: ", "512", "5000"});
}

TEST_F(CliTest, VolumeResolutionBelowTwoIsRejected) {
    expectInputError(volume({{"--res", "1"}}), {"command line: --res: ", "found 1"});
}

TEST_F(CliTest, MalformedSizeIsRejected) {
    expectInputError(slice({{"--size", "0.4"}}), {"command line: --size: ", "WIDTHxHEIGHT", "0.4"});
}

TEST_F(CliTest, NonNumericSizeIsRejected) {
    expectInputError(slice({{"--size", "abcx0.3m"}}),
                     {"command line: --size: ", "WIDTHxHEIGHT", "abcx0.3m"});
}

TEST_F(CliTest, ZeroSizeIsRejected) {
    expectInputError(slice({{"--size", "0x0.3m"}}), {"command line: --size: ", "0x0.3m"});
}

TEST_F(CliTest, NonFiniteAtIsRejected) {
    expectInputError(slice({{"--at", "inf"}}), {"command line: --at: ", "finite"});
}

TEST_F(CliTest, UnknownPlaneIsRejectedByTheParser) {
    expectFailure(slice({{"--plane", "diagonal"}}), {"--plane", "diagonal"});
}

TEST_F(CliTest, NegativeThreadCountIsRejectedByTheParser) {
    expectFailure(slice({{"--threads", "-1"}}), {"--threads"});
}

TEST_F(CliTest, MissingSkeletonOptionIsRejectedByTheParser) {
    expectFailure(slice({{"--skeleton", kOmit}}), {"--skeleton", "required"});
}

// ---------------------------------------------------------------------------------------------
// Outputs that cannot be written

TEST_F(CliTest, SliceIntoMissingFolderIsReported) {
    auto file = (out_ / "no-such-folder" / "slice.exr").string();
    expectInputError(slice({{"-o", file}}), {file + ": ", "does not exist"});
}

TEST_F(CliTest, Df3VolumeIntoMissingFolderIsReported) {
    auto folder = out_ / "no-such-folder";
    expectInputError(volume({{"-o", (folder / "volume.df3").string()}}),
                     {folder.string(), "does not exist"});
}

TEST_F(CliTest, SliceIntoReadOnlyFolderIsReported) {
    if (geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
    auto file = (out_ / "slice.exr").string();
    ASSERT_EQ(chmod(out_.c_str(), 0555), 0) << std::strerror(errno);
    auto r = slice({{"-o", file}});
    chmod(out_.c_str(), 0755);
    expectInputError(r, {file + ": ", "not writable"});
}

TEST_F(CliTest, VolumeIntoReadOnlyFolderIsReported) {
    if (geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
    auto file = (out_ / "volume.vdb").string();
    ASSERT_EQ(chmod(out_.c_str(), 0555), 0) << std::strerror(errno);
    auto r = volume({{"-o", file}});
    chmod(out_.c_str(), 0755);
    expectInputError(r, {file + ": ", "not writable"});
}

TEST_F(CliTest, OutputThatIsAFolderIsReported) {
    fs::path folder = in_ / "a-folder.exr";
    fs::create_directory(folder);
    expectInputError(slice({{"-o", folder.string()}}), {folder.string() + ": ", "folder"});
    EXPECT_TRUE(fs::is_directory(folder));
    EXPECT_TRUE(fs::is_empty(folder));
}

TEST_F(CliTest, UnknownVolumeExtensionIsRejected) {
    auto file = (out_ / "volume.png").string();
    expectInputError(volume({{"-o", file}}),
                     {file + ": ", "unsupported output file name", ".exr", ".vdb", ".df3"});
}

// A slice is documented as "an EXR image (R,G,B,A,T,knot)" and written by writeExr
// (renderer/bake/grid_writers.cpp), but writeExr lets OpenImageIO pick the format from the file
// name: `-o slice.tif` silently writes a TIFF, `-o slice.jpg` an 8-bit JPEG without the A, T and
// knot channels, and both exit 0. It should refuse names other than .exr, as `bake volume` does
// for unknown extensions.
TEST_F(CliTest, SliceRejectsNonExrOutputName) {
    for (const char* name : {"slice.tif", "slice.jpg"}) {
        SCOPED_TRACE(name);
        auto file = (out_ / name).string();
        expectInputError(slice({{"-o", file}}), {file + ": ", ".exr"});
        std::error_code ec;
        fs::remove(file, ec);
    }
}

// ---------------------------------------------------------------------------------------------
// Good bakes

TEST_F(CliTest, SliceHelpMentionsThePlane) {
    auto r = run({"bake", "slice", "--help"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("--plane"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("--res"), std::string::npos) << r.out;
    EXPECT_EQ(outputFiles(), std::vector<std::string>{});
}

TEST_F(CliTest, SliceBakeWritesExrWithChannelsAndMetadata) {
    const std::string skeleton = skeletonScene("straight-trunk.json").string();
    auto r =
        slice({{"--grain", grainScene("species/norway-spruce.json").string()}, {"--res", "32x24"}});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find("wrote " + (out_ / "slice.exr").string()), std::string::npos) << r.out;
    ASSERT_EQ(outputFiles(), std::vector<std::string>{"slice.exr"});
    // The summary: 32 x 24 samples, the rate over the sampling alone, set-up and writing apart.
    EXPECT_TRUE(std::regex_search(
        r.out, std::regex(R"(\n768 samples in [0-9.]+ s \([0-9.]+ M samples/s; set-up [0-9.]+ s, )"
                          R"(writing [0-9.]+ s\); wood [0-9.]+%, T )")))
        << r.out;

    auto img = readImage(out_ / "slice.exr");
    ASSERT_TRUE(img);
    EXPECT_EQ(img->format, "openexr");
    EXPECT_EQ(img->spec.width, 32);
    EXPECT_EQ(img->spec.height, 24);
    EXPECT_EQ(img->spec.nchannels, 6);
    EXPECT_EQ(img->spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A", "T", "knot"}));
    EXPECT_EQ(img->spec.get_string_attribute("nenrin:skeleton"), skeleton);
    EXPECT_NE(img->spec.get_string_attribute("nenrin:grain").find("\"radial_speed\":0.003"),
              std::string::npos)
        << img->spec.get_string_attribute("nenrin:grain");
    EXPECT_NE(img->spec.get_string_attribute("nenrin:slice").find("plane=cross"),
              std::string::npos);
    // Pixel -> tree space: a cross-section steps +X along a row and -Y down the image.
    double sx = 0, sy = 0, sz = 0;
    ASSERT_EQ(std::sscanf(img->spec.get_string_attribute("nenrin:sample_step_y").c_str(),
                          "%lf %lf %lf", &sx, &sy, &sz),
              3);
    EXPECT_EQ(sx, 0);
    EXPECT_LT(sy, 0);
    EXPECT_EQ(sz, 0);
    EXPECT_FALSE(img->spec.get_string_attribute("nenrin:sample_origin").empty());
    for (size_t i = 0; i < img->pixels.size(); ++i)
        ASSERT_TRUE(std::isfinite(img->pixels[i])) << "sample " << i;
    const int a = channelIndex(img->spec, "A");
    for (size_t p = a; p < img->pixels.size(); p += 6) {
        ASSERT_GE(img->pixels[p], 0.f);
        ASSERT_LE(img->pixels[p], 1.f);
    }
}

TEST_F(CliTest, SliceBakeIsBitwiseIdenticalForOneAndTwoThreads) {
    // A cross cut through broadleaf.json at 1.3 m crosses a branch, so knots are in the picture.
    Options options{{"--skeleton", skeletonScene("broadleaf.json").string()},
                    {"--grain", grainScene("species/norway-spruce.json").string()},
                    {"--at", "1.3"},
                    {"--size", "0.6x0.6m"},
                    {"--res", "48x40"}};
    std::vector<Image> images;
    for (const char* threads : {"1", "2"}) {
        Options o = options;
        o["--threads"] = threads;
        o["-o"] = (out_ / fmt::format("slice-{}.exr", threads)).string();
        auto r = slice(o);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        auto img = readImage(o["-o"]);
        ASSERT_TRUE(img);
        images.push_back(std::move(*img));
    }
    ASSERT_EQ(images[0].pixels.size(), size_t(48) * 40 * 6);
    ASSERT_EQ(images[0].pixels.size(), images[1].pixels.size());
    EXPECT_EQ(std::memcmp(images[0].pixels.data(), images[1].pixels.data(),
                          images[0].pixels.size() * sizeof(float)),
              0)
        << "1 and 2 threads differ";
    const int knot = channelIndex(images[0].spec, "knot");
    ASSERT_GE(knot, 0);
    float knotMax = 0;
    for (size_t p = knot; p < images[0].pixels.size(); p += 6)
        knotMax = std::max(knotMax, images[0].pixels[p]);
    EXPECT_GT(knotMax, 0.f) << "the slice was meant to cut a knot";
}

TEST_F(CliTest, Df3VolumeBakeWritesDensityFilesAndInclude) {
    // Longest edge along x: 8 samples over 0.4 m, fewer along y (0.2 m) and z (0.1 m).
    auto r = volume({{"--skeleton", skeletonScene("broadleaf.json").string()},
                     {"--box", "-0.2,-0.1,1.0,0.2,0.1,1.1"},
                     {"-o", (out_ / "wood.df3").string()}});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_EQ(outputFiles(), (std::vector<std::string>{"wood.B.df3", "wood.G.df3", "wood.R.df3",
                                                       "wood.inc", "wood.knot.df3"}));
    std::vector<unsigned char> header;
    for (const char* channel : {"R", "G", "B", "knot"}) {
        SCOPED_TRACE(channel);
        auto bytes = readBytes(out_ / fmt::format("wood.{}.df3", channel));
        ASSERT_GE(bytes.size(), 6u);
        const unsigned sx = bytes[0] << 8 | bytes[1], sy = bytes[2] << 8 | bytes[3],
                       sz = bytes[4] << 8 | bytes[5];
        EXPECT_EQ(sx, 8u);
        EXPECT_GE(sy, 2u);
        EXPECT_LT(sy, sx);
        EXPECT_GE(sz, 2u);
        EXPECT_LT(sz, sy);
        EXPECT_EQ(bytes.size(), 6 + 2 * size_t(sx) * sy * sz);
        if (header.empty())
            header.assign(bytes.begin(), bytes.begin() + 6);
        else
            EXPECT_TRUE(std::equal(header.begin(), header.end(), bytes.begin()));
    }
    std::string inc = readText(out_ / "wood.inc");
    for (const char* channel : {"R", "G", "B"})
        EXPECT_NE(inc.find(fmt::format("\"wood.{}.df3\"", channel)), std::string::npos) << inc;
}

TEST_F(CliTest, Df3VolumeBakeIsBitwiseIdenticalForOneAndTwoThreads) {
    for (const char* threads : {"1", "2"}) {
        auto r = volume({{"--skeleton", skeletonScene("broadleaf.json").string()},
                         {"--grain", grainScene("species/norway-spruce.json").string()},
                         {"--box", "-0.3,-0.3,1.2,0.3,0.3,1.4"},
                         {"--threads", threads},
                         {"-o", (out_ / fmt::format("t{}.df3", threads)).string()}});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    for (const char* channel : {"R", "G", "B", "knot"}) {
        auto one = readBytes(out_ / fmt::format("t1.{}.df3", channel));
        EXPECT_GT(one.size(), 6u) << channel;
        EXPECT_EQ(one, readBytes(out_ / fmt::format("t2.{}.df3", channel))) << channel;
    }
}

TEST_F(CliTest, VdbVolumeBakeWritesOneNonEmptyFile) {
    auto r = volume({{"-o", (out_ / "wood.vdb").string()}});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_EQ(outputFiles(), std::vector<std::string>{"wood.vdb"});
    auto bytes = readBytes(out_ / "wood.vdb");
    ASSERT_GE(bytes.size(), 8u);
    // OpenVDB files open with the 64-bit magic number 0x56444220 ("VDB "), little-endian.
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), std::string(" BDV"));
}

TEST_F(CliTest, ExrVolumeBakeWritesAZSliceAtlas) {
    auto r = volume({{"--box", "-0.1,-0.1,0.9,0.1,0.1,1.1"}, {"--res", "8"}});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_EQ(outputFiles(), std::vector<std::string>{"volume.exr"});
    auto img = readImage(out_ / "volume.exr");
    ASSERT_TRUE(img);
    EXPECT_EQ(img->spec.width, 8);
    EXPECT_EQ(img->spec.height, 8 * 8);
    EXPECT_EQ(img->spec.channelnames, (std::vector<std::string>{"R", "G", "B", "A", "T", "knot"}));
    EXPECT_EQ(img->spec.get_string_attribute("nenrin:volume_resolution"), "8 8 8");
    EXPECT_EQ(img->spec.get_string_attribute("nenrin:box"), "-0.1,-0.1,0.9,0.1,0.1,1.1");
}

}  // namespace
