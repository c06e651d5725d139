// End-to-end tests of bounded resources (issue 14): a job that would not fit is refused before
// it allocates, with its estimate and the limit (--max-memory, or 80 % of the machine's), one
// line, exit 1 and no output; a job that fits is not affected by the check.

#include "tests/cli/cli_fixture.h"

namespace {

const fs::path kScene = kSourceDir / "tests/data/scenes/small-glulam.json";

class MemoryLimitsCliTest : public CliTest {};

TEST_F(MemoryLimitsCliTest, AVolumeOverTheLimitIsRefusedWithItsEstimate) {
    // 512^3 samples x 6 channels x 4 bytes x 2 (samples and the writer's copy) = 6 GiB.
    expectInputError(volume({{"--res", "512"}, {"--max-memory", "4G"}}),
                     {"bake: a 512 x 512 x 512 volume needs about 6.0 GiB",
                      "over the --max-memory limit of 4.0 GiB"});
    // A bake that fits runs under a tight limit: 8^3 x 48 bytes.
    EXPECT_EQ(volume({{"--max-memory", "1M"}}).exitCode, 0);
}

TEST_F(MemoryLimitsCliTest, RenderUvBakeAndPovVolumesAreChecked) {
    expectInputError(
        run({"render", kScene.string(), "-q", "--max-memory", "512K", "-o",
             (out_ / "x.exr").string()}),
        {"small-glulam.json: a 96x64 frame needs about 960 KiB", "--max-memory limit of 512 KiB"});
    fs::create_directories(in_ / "twin");  // pov writes into an existing folder
    // The twin's df3 files count against the limit too, and their size is said first.
    const RunResult twin = run({"pov", kScene.string(), "--volume", "1024", "--max-memory", "100M",
                                "-q", "-o", (in_ / "twin").string()});
    expectInputError(twin, {"twin: writing the df3 volumes of 1 wood object at --volume 1024",
                            "over the --max-memory"});
    EXPECT_NE(twin.out.find("of df3 volumes (1 wood object at --volume 1024)"), std::string::npos)
        << twin.out;
    EXPECT_TRUE(fs::is_empty(in_ / "twin"));
    expectInputError(
        run({"pov", kScene.string(), "--volume", "1024", "--max-memory", "1G", "-q", "-o",
             (in_ / "twin").string()}),
        {"pov: the df3 volume of object", "at --volume 1024", "over the --max-memory"});
    expectInputError(
        run({"bake", "uv", "--scene", (kSourceDir / "tests/data/scenes/uv-cube.json").string(),
             "--object", "cube", "--res", "8192", "--max-memory", "1G", "-q", "-o",
             (in_ / "twin").string()}),
        {"a set of 8192x8192 texture maps needs", "over the --max-memory"});
}

TEST_F(MemoryLimitsCliTest, MalformedSizesAreRefusedByTheParser) {
    for (const char* size : {"lots", "-1G", "0", "nan", "1e30T", "8Q"})
        expectFailure(
            run({"render", kScene.string(), "--max-memory", size, "-o", (out_ / "x.exr").string()}),
            {"--max-memory", "expected a size such as 8G"});
}

TEST_F(MemoryLimitsCliTest, TinyFingerJointsAreRefusedBeforeTheLayoutIsDrawn) {
    // Pieces of 1e-6 m once grew to 24 GB before the kernel killed the process.
    expectInputError(
        run({"render", kScene.string(), "-q", "--set", "/objects/1/finger_joints/min_length=1e-6",
             "--set", "/objects/1/finger_joints/max_length=2e-6", "-o", (out_ / "x.exr").string()}),
        {"objects[1].finger_joints.min_length", "could make 7.2e+06 boards",
         "expected at most 100000"});
}

TEST_F(MemoryLimitsCliTest, DevicesAndFoldersAreNotInputFiles) {
    // /dev/zero as an OBJ once ran for minutes; as a ring series or QSM it filled memory.
    expectInputError(
        run({"tree", "import", "/dev/zero", "--format", "qsm", "-o", (out_ / "t.json").string()}),
        {"/dev/zero", "not a regular file", "QSM cylinder list"});
    expectInputError(run({"tree", "rings", "/dev/zero", "--list"}),
                     {"/dev/zero", "not a regular file", "Tucson .rwl"});
    expectInputError(
        run({"tree", "import", "/tmp", "--format", "qsm", "-o", (out_ / "t.json").string()}),
        {"/tmp", "this is a folder"});
}

}  // namespace
