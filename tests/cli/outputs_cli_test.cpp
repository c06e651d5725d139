// End-to-end tests of how outputs are written: a command's outputs reach their names together
// or not at all, and an existing target that is not a regular file is never replaced.

#include <fmt/ranges.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include "tests/cli/cli_fixture.h"

namespace {

const fs::path kScene = kSourceDir / "tests/data/scenes/small-glulam.json";
const fs::path kSceneRoom = kSourceDir / "scenes/table-top-room.json";

class OutputsCliTest : public CliTest {};

TEST_F(OutputsCliTest, AFailedPngTakesTheExrWithIt) {
    // A bad $OCIO fails the preview after the EXR was written: neither may stay.
    setenv("OCIO", (in_ / "missing.ocio").c_str(), 1);
    RunResult r = run({"render", kScene.string(), "-q", "--res", "32x20", "--spp", "1", "-o",
                       (out_ / "a.exr").string(), "--png", (out_ / "a.png").string()});
    unsetenv("OCIO");
    expectInputError(r, {"missing.ocio"});
}

TEST_F(OutputsCliTest, TargetsThatAreNotRegularFilesAreNeverReplaced) {
    const fs::path fifo = in_ / "fifo.exr", link = in_ / "link.exr", target = in_ / "target.exr";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
    std::ofstream(target) << "keep";
    fs::create_symlink(target, link);
    std::vector<std::pair<fs::path, std::string>> cases = {{fifo, "a FIFO"},
                                                           {link, "a symbolic link"}};
    // A copy of /dev/null's device node (root only: as root, `-o /dev/null` once destroyed it).
    const fs::path device = in_ / "null.exr";
    if (mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0)
        cases.push_back({device, "a character device"});
    for (const auto& [path, kind] : cases) {
        RunResult r = run(
            {"render", kScene.string(), "-q", "--res", "16x16", "--spp", "1", "-o", path.string()});
        expectInputError(r, {path.string(), kind, "not a regular file"});
    }
    EXPECT_TRUE(fs::is_fifo(fs::symlink_status(fifo)));
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
    EXPECT_EQ(readText(target), "keep");
    if (cases.size() == 3) {
        EXPECT_TRUE(fs::is_character_file(fs::symlink_status(device)));
    }
}

TEST_F(OutputsCliTest, PartialFilesOfKilledRunsAreCleanedUp) {
    // A run killed while writing leaves its temporary file; the next run of that output removes
    // it (its process is gone) but never the temporary file of a process still running.
    const fs::path stale = out_ / ".a.partial-999999999.exr";
    const fs::path live = out_ / fmt::format(".a.partial-{}.exr", getpid());
    std::ofstream(stale) << "half";
    std::ofstream(live) << "in progress";
    RunResult r = run({"render", kScene.string(), "-q", "--res", "16x16", "--spp", "1", "-o",
                       (out_ / "a.exr").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(live));
    EXPECT_TRUE(fs::exists(out_ / "a.exr"));
}

TEST_F(OutputsCliTest, AnEmptyOutputNameIsTheCommandLines) {
    // Once reported as "<input>: unsupported output file name".
    expectInputError(run({"render", kScene.string(), "-o", ""}),
                     {"command line: output: the output file name is empty", ".exr"});
    expectInputError(slice({{"-o", ""}}), {"command line: output: the output file name is empty"});
}

TEST_F(OutputsCliTest, BrokenFilesAScenePointsAtNameTheSceneToo) {
    // A broken environment map, mesh, skeleton or grain was named, but not the scene (and the
    // key in it) that refers to it.
    const fs::path bad = in_ / "broken.exr";
    std::ofstream(bad) << "not an image";
    std::ofstream(in_ / "broken.obj") << "v 0 0 0\nf 1 2 3\n";
    std::ofstream(in_ / "broken.json") << "{\"radial_speed\": -1}";
    const std::string uvCube = (kSourceDir / "tests/data/scenes/uv-cube.json").string();
    const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
        {{kSceneRoom.string(), "--set", "/lights/1/map=" + bad.string()},
         {"table-top-room.json: lights[1].map: ", "broken.exr", "cannot read the image"}},
        {{uvCube, "--set", "/objects/0/file=" + (in_ / "broken.obj").string()},
         {"uv-cube.json: objects[0].file: ", "broken.obj: line 2"}},
        {{uvCube, "--set", "/materials/0/grain=" + (in_ / "broken.json").string()},
         {"uv-cube.json: materials[0].grain: ", "broken.json: radial_speed"}}};
    for (const auto& [args, pieces] : cases) {
        std::vector<std::string> all{"render"};
        all.insert(all.end(), args.begin(), args.end());
        all.insert(all.end(), {"-q", "-o", (out_ / "x.exr").string()});
        expectInputError(run(all), pieces);
    }
}

TEST_F(OutputsCliTest, CaughtSignalsLeaveNoTemporaryFileBehind) {
    // SIGTERM (timeout, SLURM), SIGINT (Ctrl-C) and SIGHUP while a volume is being written:
    // the run ends with 128 + the signal and its hidden temporary file is gone.
    for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
        SCOPED_TRACE(strsignal(sig));
        const std::vector<std::string> args =
            bakeArgs("volume",
                     {{"--skeleton", skeletonScene("conifer.json").string()},
                      {"--box", "-0.2,-0.2,0,0.2,0.2,2"},
                      {"--res", "400"},
                      {"-o", (out_ / "v.exr").string()}},
                     {});
        std::vector<char*> argv{const_cast<char*>(kBinary.c_str())};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        const pid_t pid = fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {
            if (chdir(out_.c_str()) != 0) _exit(120);
            execv(kBinary.c_str(), argv.data());
            _exit(121);
        }
        // Wait until the volume is being written (at most two minutes, under sanitizers).
        bool writing = false;
        for (int i = 0; i < 1200 && !writing; ++i) {
            for (const std::string& f : outputFiles())
                writing = writing || f.find(".partial-") != std::string::npos;
            if (!writing) usleep(100000);
        }
        ASSERT_TRUE(writing) << "no temporary file appeared";
        ASSERT_EQ(kill(pid, sig), 0);
        int status = 0;
        ASSERT_EQ(waitpid(pid, &status, 0), pid);
        ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
        EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
        EXPECT_TRUE(outputFiles().empty()) << fmt::format("{}", fmt::join(outputFiles(), ", "));
    }
}

}  // namespace
