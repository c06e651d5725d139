// End-to-end tests of split jobs (docs/farm.md): `render/bake --tile K/N` parts merged by
// `nenrin merge` are byte-identical to the one-process job; a missing, doubled, foreign or
// damaged part is named and nothing is written; batches and `farm slurm --no-submit` scripts.

#include "tests/cli/cli_fixture.h"

namespace {

const fs::path kScene = kSourceDir / "tests/data/scenes/small-glulam.json";

class SplitCliTest : public CliTest {
protected:
    /// Renders part K/N of the small glulam scene into in/part-K.exr.
    void renderParts(int parts, const std::vector<std::string>& extra = {}) {
        for (int k = 1; k <= parts; ++k) {
            std::vector<std::string> args{"render", kScene.string(), "-q",
                                          "--res",  "64x40",         "--spp",
                                          "4",      "--tile",        fmt::format("{}/{}", k, parts),
                                          "-o",     part(k).string()};
            args.insert(args.end(), extra.begin(), extra.end());
            RunResult r = run(args);
            ASSERT_EQ(r.exitCode, 0) << r.err;
        }
    }
    fs::path part(int k) const { return in_ / fmt::format("part-{}.exr", k); }
    std::vector<std::string> merge(std::vector<int> ks, const fs::path& output) const {
        std::vector<std::string> args{"merge"};
        for (int k : ks) args.push_back(part(k).string());
        args.insert(args.end(), {"-o", output.string()});
        return args;
    }
    /// The one-process render into in/whole.exr.
    fs::path renderWhole(const std::vector<std::string>& extra = {}) {
        std::vector<std::string> args{"render",
                                      kScene.string(),
                                      "-q",
                                      "--res",
                                      "64x40",
                                      "--spp",
                                      "4",
                                      "-o",
                                      (in_ / "whole.exr").string()};
        args.insert(args.end(), extra.begin(), extra.end());
        RunResult r = run(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return in_ / "whole.exr";
    }
};

TEST_F(SplitCliTest, MergedRenderIsByteIdenticalToOneRender) {
    const fs::path whole = renderWhole();
    renderParts(3);
    auto p = readImage(part(2));
    ASSERT_TRUE(p);
    // Part 2 of 3 of 40 rows in 16-row tiles: tile rows 1..1 = rows 16..31.
    EXPECT_EQ(p->spec.y, 16);
    EXPECT_EQ(p->spec.height, 16);
    EXPECT_EQ(p->spec.full_height, 40);
    EXPECT_EQ(p->spec.get_string_attribute("nenrin:part"), "2/3");
    RunResult r = run(merge({3, 1, 2}, out_ / "merged.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(out_ / "merged.exr"), readBytes(whole));
}

TEST_F(SplitCliTest, MergedAdaptiveRenderIsByteIdentical) {
    const std::vector<std::string> adaptive{"--noise-threshold", "0.05", "--min-spp", "2"};
    const fs::path whole = renderWhole(adaptive);
    renderParts(2, adaptive);
    RunResult r = run(merge({1, 2}, out_ / "merged.exr"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(out_ / "merged.exr"), readBytes(whole));
}

TEST_F(SplitCliTest, MergedBakesAreByteIdentical) {
    for (const std::string ext : {".exr", ".vdb"}) {
        ASSERT_EQ(volume({{"--res", "24"}, {"-o", (in_ / ("whole" + ext)).string()}}).exitCode, 0);
    }
    ASSERT_EQ(slice({{"--res", "40x70"}, {"-o", (in_ / "slice.exr").string()}}).exitCode, 0);
    for (int k = 1; k <= 3; ++k) {
        RunResult r = volume({{"--res", "24"},
                              {"--tile", fmt::format("{}/3", k)},
                              {"-o", (in_ / fmt::format("v{}.exr", k)).string()}});
        ASSERT_EQ(r.exitCode, 0) << r.err;
        r = slice({{"--res", "40x70"},
                   {"--tile", fmt::format("{}/3", k)},
                   {"-o", (in_ / fmt::format("s{}.exr", k)).string()}});
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    auto partsOf = [&](const char* prefix) {
        std::vector<std::string> v;
        for (int k = 1; k <= 3; ++k)
            v.push_back((in_ / fmt::format("{}{}.exr", prefix, k)).string());
        return v;
    };
    for (const std::string ext : {".exr", ".vdb"}) {
        std::vector<std::string> args{"merge"};
        for (const auto& p : partsOf("v")) args.push_back(p);
        args.insert(args.end(), {"-o", (out_ / ("volume" + ext)).string()});
        RunResult r = run(args);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(readBytes(out_ / ("volume" + ext)), readBytes(in_ / ("whole" + ext))) << ext;
    }
    std::vector<std::string> args{"merge"};
    for (const auto& p : partsOf("s")) args.push_back(p);
    args.insert(args.end(), {"-o", (out_ / "slice.exr").string()});
    RunResult r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(out_ / "slice.exr"), readBytes(in_ / "slice.exr"));
}

TEST_F(SplitCliTest, TheSameVdbBakeGivesTheSameBytes) {
    // OpenVDB's random file UUID is replaced by one made from the content.
    ASSERT_EQ(volume({{"-o", (in_ / "a.vdb").string()}}).exitCode, 0);
    ASSERT_EQ(volume({{"-o", (in_ / "b.vdb").string()}}).exitCode, 0);
    EXPECT_EQ(readBytes(in_ / "a.vdb"), readBytes(in_ / "b.vdb"));
}

TEST_F(SplitCliTest, AMissingPartIsNamedAndNothingWritten) {
    renderParts(3);
    expectInputError(run(merge({1, 3}, out_ / "m.exr")),
                     {"missing part 2/3 (rows 16..31)", "nothing written"});
}

TEST_F(SplitCliTest, ADoubledPartIsNamed) {
    renderParts(2);
    fs::copy_file(part(1), in_ / "copy.exr");
    std::vector<std::string> args = merge({1, 2}, out_ / "m.exr");
    args.insert(args.begin() + 2, (in_ / "copy.exr").string());
    expectInputError(run(args), {"copy.exr", "part 1/2 twice"});
}

TEST_F(SplitCliTest, APartOfAnotherJobIsRefused) {
    renderParts(2);
    RunResult r = run({"render", kScene.string(), "-q", "--res", "64x40", "--spp", "4", "--seed",
                       "9", "--tile", "2/2", "-o", (in_ / "other.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    expectInputError(run({"merge", part(1).string(), (in_ / "other.exr").string(), "-o",
                          (out_ / "m.exr").string()}),
                     {"other.exr", "belongs to another job", "do not merge"});
}

TEST_F(SplitCliTest, ADamagedOrForeignFileIsRefused) {
    renderParts(2);
    // Truncated: the part's last bytes lost.
    std::string bytes = readText(part(2));
    std::ofstream(in_ / "cut.exr", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    expectInputError(run({"merge", part(1).string(), (in_ / "cut.exr").string(), "-o",
                          (out_ / "m.exr").string()}),
                     {"cut.exr"});
    // A whole render is not a part.
    const fs::path whole = renderWhole();
    expectInputError(run({"merge", whole.string(), "-o", (out_ / "m.exr").string()}),
                     {"whole.exr", "nenrin:part", "not a part of a split job"});
}

TEST_F(SplitCliTest, BadTileArgumentsAreRefused) {
    expectInputError(
        run({"render", kScene.string(), "--tile", "5/4", "-o", (out_ / "p.exr").string()}),
        {"--tile", "1 <= K <= N"});
    expectInputError(run({"render", kScene.string(), "--tile", "1/3", "--res", "16x16", "-o",
                          (out_ / "p.exr").string()}),
                     {"--tile", "use at most 1 parts"});
    expectInputError(run({"render", kScene.string(), "--tile", "1/2", "--png",
                          (out_ / "p.png").string(), "-o", (out_ / "p.exr").string()}),
                     {"--png", "give --png to nenrin merge"});
}

TEST_F(SplitCliTest, BatchFramesEqualRendersWithTheirOverrides) {
    std::ofstream(in_ / "batch.json") << fmt::format(
        R"({{"scene": "{}", "output": "frames/{{name}}.exr",
  "set": {{"/render/resolution": [32, 20], "/render/spp": 2}},
  "frames": [{{"name": "near"}}, {{"name": "far", "set": {{"/camera/fov": 20}}}}],
  "sweep": {{"/render/seed": [1, 2]}}}})",
        kScene.string());
    RunResult list = run({"batch", (in_ / "batch.json").string(), "--list"});
    ASSERT_EQ(list.exitCode, 0) << list.err;
    EXPECT_EQ(countOf(list.out, "\n"), 4u) << list.out;
    EXPECT_NE(list.out.find("3\tfar-0001\t"), std::string::npos) << list.out;
    RunResult r = run({"batch", (in_ / "batch.json").string(), "--frame", "4", "-q"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    ASSERT_TRUE(fs::exists(in_ / "frames/far-0002.exr"));
    EXPECT_FALSE(fs::exists(in_ / "frames/near-0001.exr"));
    r = run({"render", kScene.string(), "-q", "--set", "/render/resolution=[32,20]", "--set",
             "/render/spp=2", "--set", "/camera/fov=20", "--set", "/render/seed=2", "-o",
             (in_ / "ref.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readBytes(in_ / "frames/far-0002.exr"), readBytes(in_ / "ref.exr"));
}

TEST_F(SplitCliTest, BadBatchFilesAndOverridesAreRefused) {
    std::ofstream(in_ / "dup.json") << fmt::format(
        R"({{"scene": "{}", "frames": [{{"name": "a"}}, {{"name": "a"}}]}})", kScene.string());
    expectInputError(run({"batch", (in_ / "dup.json").string(), "--list"}),
                     {"dup.json", "two frames named \"a\""});
    std::ofstream(in_ / "sweep.json")
        << fmt::format(R"({{"scene": "{}", "sweep": {{"/render/seed": 3}}}})", kScene.string());
    expectInputError(run({"batch", (in_ / "sweep.json").string(), "--list"}),
                     {"sweep.json", "sweep", "non-empty list"});
    expectInputError(run({"render", kScene.string(), "--set", "/nowhere/seed=1", "-o",
                          (out_ / "x.exr").string()}),
                     {"/nowhere/seed", "parent does not exist"});
    expectInputError(run({"render", kScene.string(), "--set", "/render/sped=1", "-o",
                          (out_ / "x.exr").string()}),
                     {"render.sped", "unknown key"});
}

TEST_F(SplitCliTest, SlurmScriptsChainTheMergeAfterTheTasks) {
    RunResult r =
        run({"farm", "slurm", "--no-submit", "--tiles", "4", "--job-dir", (in_ / "job").string(),
             "--cpus-per-task", "2", "--partition", "render", "render", kScene.string(), "--spp",
             "8", "-o", (in_ / "final.exr").string(), "--png", (in_ / "final.png").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string tasks = readText(in_ / "job/tasks.sbatch");
    EXPECT_NE(tasks.find("#SBATCH --array=1-4\n"), std::string::npos) << tasks;
    EXPECT_NE(tasks.find("#SBATCH --partition=render\n"), std::string::npos) << tasks;
    EXPECT_NE(tasks.find("'--tile' ''\"$k\"'/4'"), std::string::npos) << tasks;
    EXPECT_NE(tasks.find("'--threads' '2'"), std::string::npos) << tasks;
    const std::string merge = readText(in_ / "job/merge.sbatch");
    EXPECT_NE(merge.find("part-4.exr' '-o'"), std::string::npos) << merge;
    EXPECT_NE(merge.find("'--png'"), std::string::npos) << merge;
    const std::string submit = readText(in_ / "job/submit.sh");
    EXPECT_NE(submit.find("--dependency=afterok:\"$tasks\" --kill-on-invalid-dep=yes"),
              std::string::npos)
        << submit;
    // Every script is valid bash.
    for (const char* f : {"tasks.sbatch", "merge.sbatch", "submit.sh", "retry.sh"})
        EXPECT_EQ(
            std::system(fmt::format("bash -n {}", shellQuote((in_ / "job" / f).string())).c_str()),
            0)
            << f;
    expectInputError(run({"farm", "slurm", "--no-submit", "render", kScene.string(), "-o",
                          (out_ / "f.exr").string()}),
                     {"--tiles", "missing"});
    expectInputError(run({"farm", "slurm", "--no-submit", "--tiles", "2", "render", kScene.string(),
                          "--tile", "1/2", "-o", (out_ / "f.exr").string()}),
                     {"--tile", "the job sets this itself"});
}

}  // namespace
