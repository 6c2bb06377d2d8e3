// End-to-end tests of what a new user meets in the first hour (issue 20): OpenMP threads that
// sleep while they wait, the features `weir info` names, output folders that are not mixed, counts
// with suffixes, errors that name each command's own options, scene names with a did-you-mean,
// honest frame-0 statistics, and the last line of a run.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "cli/cli_test_support.h"
#include "io/frame_reader.h"

namespace weir {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace cli_testing;

// 6 x 6 x 4 particles at 2 cm: tiny, and a run of a few frames takes well under a second.
constexpr const char* kCpu = " --backend cpu --quiet";

// The last value libgomp's OMP_DISPLAY_ENV=verbose printed for GOMP_SPINCOUNT (how long a waiting
// thread spins before it sleeps), or "" for another OpenMP runtime.
std::string lastSpinCount(const std::string& output) {
    std::string last;
    const std::regex line(R"(GOMP_SPINCOUNT = '(\d+)')");
    for (auto it = std::sregex_iterator(output.begin(), output.end(), line);
         it != std::sregex_iterator(); ++it) {
        last = (*it)[1];
    }
    return last;
}

TEST_F(Cli, OpenMpThreadsSleepWhileWaitingUnlessTheUserChose) {
    const std::string weirPath = quoted(WEIR_BINARY);
    const RunResult unset =
        shell("env -u OMP_WAIT_POLICY OMP_DISPLAY_ENV=verbose " + weirPath + " info");
    ASSERT_EQ(unset.exitCode, 0) << unset.output;
    EXPECT_TRUE(contains(unset.output, "OpenMP wait policy: passive (weir's default"));
    const std::string spins = lastSpinCount(unset.output);
    if (spins.empty()) {
        GTEST_SKIP() << "not libgomp: its spin count cannot be read";
    }
    EXPECT_EQ(spins, "0") << unset.output;  // the runtime itself sleeps at once

    const RunResult active =
        shell("OMP_WAIT_POLICY=active OMP_DISPLAY_ENV=verbose " + weirPath + " info");
    ASSERT_EQ(active.exitCode, 0) << active.output;
    EXPECT_TRUE(contains(active.output, "OpenMP wait policy: active (from OMP_WAIT_POLICY)"));
    EXPECT_NE(lastSpinCount(active.output), "0") << active.output;
}

TEST_F(Cli, InfoListsTheFeaturesBuiltIn) {
    const RunResult info = weir("info");
    ASSERT_EQ(info.exitCode, 0) << info.output;
    EXPECT_TRUE(contains(info.output, "built in:"));
#if defined(WEIR_HAS_CUDA)
    EXPECT_TRUE(contains(info.output, "CUDA backend: yes"));
#else
    EXPECT_TRUE(contains(info.output, "CUDA backend: no"));
#endif
#if defined(WEIR_HAS_RENDER)
    EXPECT_TRUE(contains(info.output, "rendering: yes"));
#else
    EXPECT_TRUE(contains(info.output, "rendering: no"));
#endif
#if defined(WEIR_HAS_MPI)
    EXPECT_TRUE(contains(info.output, "MPI: yes"));
#else
    EXPECT_TRUE(contains(info.output, "MPI: no"));
#endif
#if defined(WEIR_HAS_NCCL)
    EXPECT_TRUE(contains(info.output, "NCCL: yes"));
#else
    EXPECT_TRUE(contains(info.output, "NCCL: no"));
#endif
    EXPECT_TRUE(contains(info.output,
                         sizeof(Real) == 8 ? "double precision: yes" : "double precision: no"));
}

// --- set-up -------------------------------------------------------------------------------

// `cmake --install` (what scripts/setup.sh runs) puts a weir that works from anywhere into
// PREFIX/bin: the built-in scenes travel inside it.
TEST_F(Cli, TheInstallStepPutsAWorkingWeirIntoPrefixBin) {
    if (!onPath("cmake")) {
        GTEST_SKIP() << "no cmake on PATH";
    }
    const fs::path build = fs::path(WEIR_BINARY).parent_path();
    const RunResult install =
        shell("cmake --install " + quoted(build.string()) + " --prefix " + quoted(path("prefix")));
    ASSERT_EQ(install.exitCode, 0) << install.output;
    const fs::path installed = dir_ / "prefix" / "bin" / "weir";
    ASSERT_TRUE(fs::exists(installed)) << install.output;
    fs::create_directories(dir_ / "elsewhere");
    const RunResult run = shell("cd elsewhere && PATH=" + quoted((dir_ / "prefix/bin").string()) +
                                ":$PATH weir run drop_into_pool -n 300 --frames 0 --backend cpu");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(fs::exists(dir_ / "elsewhere/out/drop_into_pool/frame_00000.vtu"));
    // And the set-up script runs that step, saying where the binary went.
    const std::string setup = fileText(fs::path(WEIR_SOURCE_DIR) / "scripts/setup.sh");
    EXPECT_TRUE(contains(setup, "cmake --install"));
}

TEST(Licence, IsShippedAndNamedInTheReadme) {
    const fs::path source(WEIR_SOURCE_DIR);
    const std::string licence = fileText(source / "LICENSE");
    EXPECT_TRUE(contains(licence, "MIT License"));
    EXPECT_TRUE(contains(licence, "Permission is hereby granted, free of charge"));
    EXPECT_TRUE(contains(fileText(source / "README.md"), "[MIT License](LICENSE)"));
}

// --- output folders -----------------------------------------------------------------------

// The pid of a process that has ended (a child, reaped): what a killed run's temporaries carry.
std::string endedProcess() {
    const pid_t child = ::fork();
    if (child == 0) {
        ::_exit(0);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    return std::to_string(child);
}

std::string otherScene() {
    std::string text = kTinyDrawScene;
    text.replace(text.find("\"tiny\""), 6, "\"other\"");
    return text;
}

TEST_F(Cli, ARunRefusesAFolderWithAnotherRunsFramesUnlessOverwrite) {
    writeFile("tiny.json", kTinyDrawScene);
    writeFile("other.json", otherScene());
    ASSERT_EQ(weir("run tiny.json" + std::string(kCpu) + " --frames 3 --mesh --out f").exitCode, 0);
    const std::vector<std::string> before = entries(dir_ / "f");
    const std::vector<std::string> meshes = entries(dir_ / "f/mesh");
    ASSERT_EQ(meshes.size(), 8u);  // frames 0..3, obj and ply

    const RunResult refused = weir("run other.json" + std::string(kCpu) + " --frames 1 --out f");
    EXPECT_EQ(refused.exitCode, 2) << refused.output;
    EXPECT_TRUE(
        contains(refused.output, "f/ holds the 4 frames of an earlier run of scene 'tiny'"));
    EXPECT_TRUE(contains(refused.output, "--overwrite"));
    EXPECT_EQ(entries(dir_ / "f"), before);  // untouched
    EXPECT_EQ(entries(dir_ / "f/mesh"), meshes);
    EXPECT_EQ(Json::parse(fileText(dir_ / "f/frames.json"))["count"], 4);

    // The same scene again is another run too: its frames would mix with the earlier ones.
    const RunResult again = weir("run tiny.json" + std::string(kCpu) + " --frames 1 --out f");
    EXPECT_EQ(again.exitCode, 2) << again.output;

    const RunResult replaced =
        weir("run other.json" + std::string(kCpu) + " --frames 1 --out f --overwrite");
    ASSERT_EQ(replaced.exitCode, 0) << replaced.output;
    EXPECT_TRUE(
        contains(replaced.output, "removed the 4 frames of an earlier run of scene 'tiny'"));
    EXPECT_EQ(entries(dir_ / "f"),
              (std::vector<std::string>{"frame.pvd", "frame_00000.vtu", "frame_00001.vtu",
                                        "frames.json", "mesh"}));
    EXPECT_TRUE(entries(dir_ / "f/mesh").empty());  // the old run's surfaces went with it
    const Json index = Json::parse(fileText(dir_ / "f/frames.json"));
    EXPECT_EQ(index["count"], 2);
    EXPECT_EQ(index["scene"]["name"], "other");
    const std::string pvd = fileText(dir_ / "f/frame.pvd");
    EXPECT_FALSE(contains(pvd, "frame_00003.vtu"));
}

TEST_F(Cli, TheTemporariesOfAKilledRunAreRemovedByTheNextRun) {
    writeFile("tiny.json", kTinyDrawScene);
    const std::string dead = endedProcess();
    fs::create_directories(dir_ / "f/images");
    writeFile("f/frame_00002.vtu.tmp." + dead + ".0", "half a frame");
    writeFile("f/frames.json.tmp." + dead + ".5", "{");
    writeFile("f/images/frame_00001.png.tmp." + dead + ".1", "half an image");
    writeFile("f/notes.txt", "the user's");
    const RunResult run = weir("run tiny.json" + std::string(kCpu) + " --frames 1 --out f");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "removed 3 temporary files that a killed run left in f/"));
    EXPECT_EQ(entries(dir_ / "f"),
              (std::vector<std::string>{"frame.pvd", "frame_00000.vtu", "frame_00001.vtu",
                                        "frames.json", "images", "notes.txt"}));
    EXPECT_TRUE(entries(dir_ / "f/images").empty());
}

TEST_F(Cli, FramesJsonRecordsTheScene) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json" + std::string(kCpu) + " --frames 0 --out f").exitCode, 0);
    const Json index = Json::parse(fileText(dir_ / "f/frames.json"));
    EXPECT_EQ(index["scene"]["name"], "tiny");
    EXPECT_EQ(fs::path(index["scene"]["source"].get<std::string>()),
              (dir_ / "tiny.json").lexically_normal());
    EXPECT_EQ(index["scene"]["definition"], Json::parse(kTinyDrawScene));
    EXPECT_EQ(index["particles"], 144);
    EXPECT_DOUBLE_EQ(index["spacing"].get<double>(), 0.02);

    ASSERT_EQ(weir("run dam_break -n 300" + std::string(kCpu) + " --frames 0 --out d").exitCode, 0);
    const Json builtin = Json::parse(fileText(dir_ / "d/frames.json"));
    EXPECT_EQ(builtin["scene"]["source"], "<built-in dam_break>");
    EXPECT_EQ(builtin["scene"]["definition"]["container"]["max"][0], 1.6);
}

// --- what a run reports -------------------------------------------------------------------

// A ball of water that overlaps a block: seeded on their own lattices, the two meet closer than
// the spacing, so the initial state is compressed. The paper's model: its density is summed from
// positions, so frame 0 shows it (delta-SPH's starts hydrostatic, from the seeding).
constexpr const char* kTouchingScene = R"({
    "name": "touching",
    "container": {"min": [0, 0, 0], "max": [0.3, 0.2, 0.08]},
    "blocks": [{"min": [0, 0, 0], "max": [0.12, 0.12, 0.08]}],
    "spheres": [{"center": [0.15, 0.04, 0.04], "radius": 0.035}],
    "fluid": {"model": "paper"},
    "particles": {"spacing": 0.01},
    "time": {"duration": 1, "frameRate": 30}
})";

TEST_F(Cli, FrameZerosStatisticsAreThoseOfItsFile) {
    writeFile("touching.json", kTouchingScene);
    const RunResult run =
        weir("run touching.json" + std::string(kCpu) + " --frames 0 --format csv --out f");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const HostParticles first = readCsv(path("f/frame_00000.csv"));
    double densest = 0;
    for (Real rho : first.rho) {
        densest = std::max(densest, double(rho));
    }
    const double percent = 100 * (densest - 1000) / 1000;
    ASSERT_GT(percent, 5.0);  // the scene does what it is for
    char expected[64];
    std::snprintf(expected, sizeof expected, "density +%.2f%% max", percent);
    EXPECT_TRUE(contains(run.output, "frame 0 (the initial state): " + std::string(expected)));
    EXPECT_TRUE(contains(run.output, "worst frame: " + std::string(expected)));
    EXPECT_TRUE(contains(run.output, "warning: the initial fluid is compressed"));
}

TEST_F(Cli, TheLastLineOfARunSaysWhereTheFramesAreAndHowToOpenThem) {
    writeFile("tiny.json", kTinyDrawScene);
    for (const auto& [format, how] : std::vector<std::pair<std::string, std::string>>{
             {"vtu", "open f_vtu/frame.pvd in ParaView"},
             {"ply", "open the f_ply/frame_NNNNN.ply point clouds in Blender"},
             {"csv", "open the f_csv/frame_NNNNN.csv tables"}}) {
        SCOPED_TRACE(format);
        const RunResult run = weir("run tiny.json" + std::string(kCpu) + " --frames 1 --format " +
                                   format + " --out f_" + format);
        ASSERT_EQ(run.exitCode, 0) << run.output;
        std::string last = run.output.substr(0, run.output.find_last_not_of('\n') + 1);
        last = last.substr(last.find_last_of('\n') + 1);
        EXPECT_TRUE(contains(last, "weir: 2 frames in f_" + format + "/: " + how));
        EXPECT_TRUE(contains(last, "weir render f_" + format));
    }
}

// No figure in a run's log carries more than four significant digits (counts are whole).
TEST_F(Cli, FiguresInTheLogAreRoundedToWhatTheyMean) {
    writeFile("tiny.json", kTinyDrawScene);
    const RunResult run = weir("run tiny.json --backend cpu --frames 2 --out f");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, " ms (adaptive)"));
    const std::regex decimal(R"(\d+\.\d+)");
    for (auto it = std::sregex_iterator(run.output.begin(), run.output.end(), decimal);
         it != std::sregex_iterator(); ++it) {
        std::string digits = it->str();
        digits.erase(std::remove(digits.begin(), digits.end(), '.'), digits.end());
        digits.erase(0, digits.find_first_not_of('0'));
        EXPECT_LE(digits.size(), 4u) << it->str() << " in:\n" << run.output;
    }
}

// --- messages -----------------------------------------------------------------------------

TEST_F(Cli, CountsTakeSuffixesEverywhereWithRangeErrorsNamingTheLimit) {
    writeFile("tiny.json", kTinyDrawScene);
    const RunResult run = weir("run tiny.json" + std::string(kCpu) + " --frames 0 -n 0.2k");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "done, 1 frames")) << run.output;

    for (const char* command : {"run --particles 5e9", "view --particles 5e9"}) {
        SCOPED_TRACE(command);
        const RunResult tooMany = weir(command);
        EXPECT_EQ(tooMany.exitCode, 2) << tooMany.output;
        EXPECT_TRUE(contains(tooMany.output, "--particles: 5e9 is more than 2147483647"));
        EXPECT_TRUE(contains(tooMany.output, "the most particles one run holds"));
    }
    const RunResult sizes = weir("bench --sizes 10k,5e9 --no-plot --out b");
    EXPECT_EQ(sizes.exitCode, 2) << sizes.output;
    EXPECT_TRUE(contains(sizes.output, "--sizes: 5e9 is more than 2147483647"));
    const RunResult word = weir("run --particles many");
    EXPECT_EQ(word.exitCode, 2) << word.output;
    EXPECT_TRUE(contains(word.output, "'many' is not a count: write e.g. 20000, 20k, 5M or 1e9"));
    const RunResult frames = weir("run tiny.json" + std::string(kCpu) + " --frames 1e0 --out f");
    EXPECT_EQ(frames.exitCode, 0) << frames.output;
    EXPECT_TRUE(contains(frames.output, "done, 2 frames")) << frames.output;
}

TEST_F(Cli, UnknownSceneNamesListTheBuiltInScenesWithADidYouMean) {
    const RunResult slip = weir("run dambreak" + std::string(kCpu));
    EXPECT_EQ(slip.exitCode, 1) << slip.output;
    EXPECT_TRUE(contains(slip.output, "scene 'dambreak'"));
    EXPECT_TRUE(contains(slip.output, "did you mean 'dam_break'?"));
    EXPECT_TRUE(contains(slip.output,
                         "dam_break, dam_break_obstacle, double_dam_break, "
                         "drop_into_pool, floating_boxes, geyser, hose_filling_glass, "
                         "piston_wave_maker, "
                         "splash_on_sphere, tsunami_on_step, viscous_pour, wave_tank"));

#if defined(WEIR_HAS_RENDER)  // without rendering, `weir view` stops before reading a scene
    const RunResult part = weir("view pool");
    EXPECT_EQ(part.exitCode, 1) << part.output;
    EXPECT_TRUE(contains(part.output, "did you mean 'drop_into_pool'?"));
#endif

    const RunResult asFile = weir("run dam_break.json" + std::string(kCpu));
    EXPECT_EQ(asFile.exitCode, 1) << asFile.output;
    EXPECT_TRUE(contains(asFile.output, "cannot open the file"));
    EXPECT_TRUE(contains(asFile.output, "did you mean 'dam_break'?"));

    const RunResult bench = weir("bench dambrake --sizes 400 --no-plot --out b");
    EXPECT_EQ(bench.exitCode, 1) << bench.output;
    EXPECT_TRUE(contains(bench.output, "did you mean 'dam_break'?"));
    EXPECT_FALSE(fs::exists(path("out")));
}

TEST_F(Cli, AFolderNamedLikeABuiltInSceneDoesNotHideIt) {
    // From out/, the output folder of an earlier `weir run dam_break` is out/dam_break/.
    fs::create_directories(dir_ / "dam_break");
    const RunResult run = weir("run dam_break -n 300 --frames 0 --out f" + std::string(kCpu));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "scene dam_break (<built-in dam_break>)"));
}

TEST_F(Cli, EachCommandsErrorsNameItsOwnOptions) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json" + std::string(kCpu) + " --frames 0 --out frames").exitCode, 0);
    const RunResult mesh = weir("mesh frames --format stl");
    EXPECT_EQ(mesh.exitCode, 2) << mesh.output;
    EXPECT_TRUE(contains(mesh.output, "--format 'stl'"));
    EXPECT_FALSE(contains(mesh.output, "--mesh-format")) << mesh.output;

    const RunResult run = weir("run tiny.json" + std::string(kCpu) + " --mesh --mesh-format stl");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_TRUE(contains(run.output, "--mesh-format 'stl'"));

    const RunResult bench = weir("bench --sizes 400 --backends cpu-fast --no-plot --out b");
    EXPECT_EQ(bench.exitCode, 2) << bench.output;
    EXPECT_TRUE(contains(bench.output, "--backends"));
}

}  // namespace
}  // namespace weir
