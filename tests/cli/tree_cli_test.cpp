// End-to-end tests of `nenrin tree ...`: importing measured trees, previews, and the bake of a
// board from an imported tree; bad input ends in one located error and no output.

#include <nlohmann/json.hpp>

#include "tests/cli/cli_fixture.h"

namespace {

class TreeCliTest : public CliTest {
protected:
    fs::path writeInput(const std::string& name, const std::string& body) {
        fs::path p = in_ / name;
        std::ofstream(p) << body;
        return p;
    }
};

TEST_F(TreeCliTest, ImportsGran1AndBakesABoardWithDeadKnots) {
    fs::path tree = out_ / "gran1.json";
    RunResult r = run({"tree", "import", (kSourceDir / "data/gran1").string(), "-o", tree.string(),
                       "--rings", "50"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("108 knots"), std::string::npos) << r.out;
    nlohmann::json j = nlohmann::json::parse(readText(tree));
    EXPECT_EQ(j["source"]["model"], "gran1");
    EXPECT_EQ(j["branches"].size(), 108u);
    EXPECT_EQ(j["ring_widths"].size(), 50u);
    // A tangential board 30 mm off the pith through the lower knots: the knot channel shows
    // them, the felled log (T <= 50 years) covers the board.
    fs::path board = out_ / "board.exr";
    r = run({"bake", "slice", "--skeleton", tree.string(), "--plane", "tangential", "--at", "0.03",
             "--size", "0.2x0.5m", "--res", "40x100", "--bottom", "0.2", "-o", board.string(),
             "--png", (out_ / "board.png").string(), "-q"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto img = readImage(board);
    ASSERT_TRUE(img);
    int knot = channelIndex(img->spec, "knot");
    ASSERT_GE(knot, 0);
    size_t knotted = 0, n = size_t(img->spec.width) * img->spec.height;
    for (size_t i = 0; i < n; ++i) knotted += img->pixels[i * img->spec.nchannels + knot] > 0.5f;
    EXPECT_GT(knotted, n / 200) << "no knots on a board through 0.2 … 0.7 m of Gran_1";
    EXPECT_LT(knotted, n / 3);
    EXPECT_TRUE(fs::exists(out_ / "board.png"));
}

TEST_F(TreeCliTest, ImportsAQsmAndPreviewsIt) {
    fs::path qsm = writeInput("tree.txt",
                              "0.10\t1\t0\t0\t0\t0\t0\t1\t0\t2\t1\n"
                              "0.08\t1\t0\t0\t1\t0\t0\t1\t1\t0\t1\n"
                              "0.03\t0.8\t0.08\t0\t1.2\t1\t0\t0.5\t2\t0\t2\n");
    fs::path tree = out_ / "tree.json", png = out_ / "tree.png";
    RunResult r = run({"tree", "import", qsm.string(), "-o", tree.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("3 cylinders in 2 branches"), std::string::npos) << r.out;
    r = run({"tree", "preview", tree.string(), "-o", png.string(), "--res", "60x80", "--spp", "2"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    auto img = readImage(png);
    ASSERT_TRUE(img);
    EXPECT_EQ(img->spec.width, 60);
    // The stem is in the middle of the picture: some centre-column pixel is dark bark, the
    // corners are sky.
    float darkest = 1;
    for (int y = 0; y < 80; ++y)
        darkest = std::min(darkest, img->pixels[(size_t(y) * 60 + 30) * img->spec.nchannels]);
    EXPECT_LT(darkest, 0.5f);
    EXPECT_GT(img->pixels[0], 0.6f);
}

TEST_F(TreeCliTest, BadQsmNamesTheLine) {
    fs::path qsm = writeInput("bad.txt",
                              "0.10\t1\t0\t0\t0\t0\t0\t1\t0\t2\t1\n"
                              "0.08\t1\t0\t0\t1\t0\t0\t1\t7\t0\t1\n");
    expectInputError(run({"tree", "import", qsm.string(), "-o", (out_ / "t.json").string()}),
                     {"bad.txt", "line 2", "parent cylinder 7"});
}

TEST_F(TreeCliTest, UnknownFormatAndMissingFilesAreReported) {
    expectInputError(
        run({"tree", "import", (in_ / "tree.xyz").string(), "-o", (out_ / "t.json").string()}),
        {"tree.xyz", "cannot tell the format"});
    expectInputError(
        run({"tree", "preview", (in_ / "none.json").string(), "-o", (out_ / "t.png").string()}),
        {"none.json"});
    fs::path qsm = writeInput("t.txt", "0.1\t1\t0\t0\t0\t0\t0\t1\t0\t0\t1\n");
    expectInputError(run({"tree", "import", qsm.string(), "-o", (out_ / "t.png").string()}),
                     {".json"});
}

// `nenrin tree rings`: the measured ring series of data/rings listed, and one given to a
// skeleton whose layout stays as written.
TEST_F(TreeCliTest, RingSeriesAreListedAndGivenToASkeleton) {
    fs::path rwl = kSourceDir / "data/rings/nm580.rwl";
    RunResult r = run({"tree", "rings", rwl.string(), "--list"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("119 series"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("BCS05B       1370   1990    621"), std::string::npos) << r.out;
    fs::path tree = out_ / "measured.json";
    r = run({"tree", "rings", rwl.string(), "--series", "BCS05B", "--skeleton",
             skeletonScene("straight-trunk.json").string(), "-o", tree.string(), "--mean-width",
             "2.5"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(readText(tree));
    ASSERT_EQ(j["ring_widths"].size(), 621u);
    double sum = 0;
    for (double w : j["ring_widths"]) sum += w;
    EXPECT_NEAR(sum / 621, 0.0025, 1e-12);
    EXPECT_EQ(j["source"]["ring_series"]["series"], "BCS05B");
    // The written skeleton bakes.
    r = run({"bake", "slice", "--skeleton", tree.string(), "--plane", "cross", "--at", "0.5",
             "--size", "0.1x0.1m", "--res", "32x32", "-o", (out_ / "c.exr").string(), "-q"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST_F(TreeCliTest, BadRingSeriesAreReportedWithoutOutput) {
    fs::path bad = writeInput("bad.rwl",
                              "AB01    1990   100   200   300   400   500   600   700   800   "
                              "900  1000\nAB01    2000   100   -50   999\n");
    // The list shows the bad series with its line; using it is the error.
    RunResult listed = run({"tree", "rings", bad.string(), "--list"});
    EXPECT_EQ(listed.exitCode, 0) << listed.err;
    EXPECT_NE(listed.out.find("AB01         1990 BAD line 2: series 'AB01', year 2001: width -50 "
                              "is negative"),
              std::string::npos)
        << listed.out;
    expectInputError(
        run({"tree", "rings", bad.string(), "--series", "AB01", "--skeleton",
             skeletonScene("straight-trunk.json").string(), "-o", (out_ / "t.json").string()}),
        {"bad.rwl", "line 2", "negative"});
    fs::path rwl = kSourceDir / "data/rings/co021.rwl";
    expectInputError(
        run({"tree", "rings", rwl.string(), "--series", "NOPE", "--skeleton",
             skeletonScene("straight-trunk.json").string(), "-o", (out_ / "t.json").string()}),
        {"co021.rwl", "no series 'NOPE'", "641114"});
    expectInputError(run({"tree", "rings", rwl.string()}), {"--list"});
}

// `nenrin grain strip`: the photographed strip measured into grain colour keys that bake.
TEST_F(TreeCliTest, GrainStripWritesColoursThatBake) {
    fs::path grain = out_ / "strip.json";
    RunResult r =
        run({"grain", "strip", (kSourceDir / "data/colour-bars/spruce_bar_color.bmp").string(),
             "--grain", grainScene("species/norway-spruce.json").string(), "-o", grain.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("42 rings"), std::string::npos) << r.out;
    nlohmann::json j = nlohmann::json::parse(readText(grain));
    EXPECT_EQ(j["colour"]["late_wood_profile"].size(), 33u);
    EXPECT_EQ(j["radial_speed"], 0.003);  // the base grain's other keys are kept
    r = run({"bake", "slice", "--skeleton", skeletonScene("straight-trunk.json").string(),
             "--grain", grain.string(), "--plane", "cross", "--at", "1", "--size", "0.1x0.1m",
             "--res", "16x16", "-o", (out_ / "c.exr").string(), "-q"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
}

TEST_F(TreeCliTest, GrainStripRefusesWhatIsNoStrip) {
    fs::path flat = writeInput("flat.json", "{}");
    expectInputError(run({"grain", "strip", flat.string(), "-o", (out_ / "g.json").string()}),
                     {"flat.json", "cannot read the image"});
}

TEST_F(TreeCliTest, EarlywoodAndLatewoodFilesGiveYearlyLatewoodShares) {
    fs::path tree = out_ / "el.json";
    RunResult r =
        run({"tree", "rings", (kSourceDir / "data/rings/nm580e.rwl").string(), "--latewood",
             (kSourceDir / "data/rings/nm580l.rwl").string(), "--series", "BCS05B", "--skeleton",
             skeletonScene("straight-trunk.json").string(), "-o", tree.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(readText(tree));
    ASSERT_EQ(j["latewood_shares"].size(), j["ring_widths"].size());
    double lo = 1, hi = 0;
    for (double s : j["latewood_shares"]) lo = std::min(lo, s), hi = std::max(hi, s);
    EXPECT_GT(lo, 0);
    EXPECT_LT(hi, 1);
    EXPECT_GT(hi - lo, 0.2);  // measured cores: the share changes from year to year
}

}  // namespace

namespace {

class TreeModelCliTest : public CliTest {};

TEST_F(TreeModelCliTest, EveryModelWritesALoadableSkeletonAndRepeatsForItsSeed) {
    const std::vector<std::vector<std::string>> commands = {
        {"tree", "hayashi", "--preset", "hinoki", "--years", "8"},
        {"tree", "akagi", "--preset", "keyaki", "--years", "20"},
        {"tree", "kanayama", "--preset", "zelkova", "--years", "6", "-q"},
    };
    for (const auto& base : commands) {
        std::vector<std::string> a = base, b = base;
        fs::path pa = out_ / ("a-" + base[1] + ".json"), pb = out_ / ("b-" + base[1] + ".json");
        a.insert(a.end(), {"--seed", "4", "-o", pa.string()});
        b.insert(b.end(), {"--seed", "4", "-o", pb.string()});
        RunResult ra = run(a);
        ASSERT_EQ(ra.exitCode, 0) << ra.err;
        ASSERT_EQ(run(b).exitCode, 0);
        EXPECT_EQ(readBytes(pa), readBytes(pb)) << base[1] << ": same seed, other bytes";
        nlohmann::json j = nlohmann::json::parse(readText(pa));
        EXPECT_EQ(j["source"]["model"], base[1]);
        EXPECT_FALSE(j["branches"].empty()) << base[1];
        // The file is a skeleton the bake takes.
        RunResult bake = run({"bake", "slice", "--skeleton", pa.string(), "--plane", "cross",
                              "--at", "0.3", "--res", "16x16", "--size", "0.2x0.2m", "-q", "-o",
                              (out_ / ("x-" + base[1] + ".exr")).string()});
        EXPECT_EQ(bake.exitCode, 0) << base[1] << ": " << bake.err;
    }
}

TEST_F(TreeModelCliTest, StandFellsItsDominantAndSuppressedTrees) {
    // Everything good goes to the input folder: the last, failing fell must leave out_ empty.
    fs::path stand = in_ / "stand.json";
    RunResult r = run({"stand", "kunii", "--trees", "40", "--years", "40", "--seed", "2", "-q",
                       "-o", stand.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::vector<double> meanWidth;
    for (const char* pick : {"dominant", "suppressed"}) {
        fs::path tree = in_ / (std::string(pick) + ".json");
        r = run({"stand", "fell", stand.string(), "--tree", pick, "-o", tree.string()});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        nlohmann::json j = nlohmann::json::parse(readText(tree));
        double sum = 0;
        for (double w : j["ring_widths"]) sum += w;
        meanWidth.push_back(sum / j["ring_widths"].size());
    }
    EXPECT_GT(meanWidth[0], 1.5 * meanWidth[1]) << "the dominant tree's rings are not wider";
    expectInputError(run({"stand", "fell", stand.string(), "--tree", "tallest", "-o",
                          (out_ / "t.json").string()}),
                     {"--tree", "dominant"});
}

TEST_F(TreeModelCliTest, AYoungStandIsWrittenWithoutASuppressedTree) {
    // A 15-year stand once wrote its file and then exited 1: no tree was old enough to be
    // called suppressed. The stand is fine; felling "suppressed" from it is the error.
    fs::path stand = in_ / "young.json";
    RunResult r =
        run({"stand", "kunii", "--trees", "10", "--years", "15", "-q", "-o", stand.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("most suppressed living tree (>= 20 years old): none yet"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(stand));
    expectInputError(run({"stand", "fell", stand.string(), "--tree", "suppressed", "-o",
                          (out_ / "t.json").string()}),
                     {"no living tree at least 20 years old"});
}

TEST_F(TreeModelCliTest, UnknownPresetsAreNamed) {
    expectInputError(
        run({"tree", "hayashi", "--preset", "larch", "-o", (out_ / "t.json").string()}),
        {"larch", "sugi"});
    expectInputError(
        run({"tree", "kanayama", "--preset", "oak", "-q", "-o", (out_ / "t.json").string()}),
        {"oak", "cherry"});
    expectInputError(run({"tree", "akagi", "--preset", "sakura", "-o", (out_ / "t.json").string()}),
                     {"sakura", "keyaki"});
}

}  // namespace
