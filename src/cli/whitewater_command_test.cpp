// End-to-end tests of `weir whitewater` and `weir run --whitewater`: a whitewater file per frame
// and an index that lists them, the same bytes from both, and a clear error for a folder that is
// not a run's.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_test_support.h"
#include "whitewater/whitewater_files.h"
#include "whitewater/whitewater_ply.h"

namespace weir {
namespace {

using namespace cli_testing;

// Two blocks of water thrown at each other at 3 m/s in a narrow tank: they collide within the
// first frame and splash. 2 x (8 x 8 x 4) particles at 1 cm.
constexpr const char* kCollidingBlocksScene = R"({
    "name": "colliding_blocks",
    "container": {"min": [0, 0, 0], "max": [0.3, 0.2, 0.04]},
    "blocks": [{"min": [0.02, 0, 0], "max": [0.1, 0.08, 0.04], "velocity": [3, 0, 0]},
               {"min": [0.2, 0, 0], "max": [0.28, 0.08, 0.04], "velocity": [-3, 0, 0]}],
    "particles": {"spacing": 0.01},
    "time": {"duration": 1, "frameRate": 30}
})";

class WhitewaterCli : public Cli {};

TEST_F(WhitewaterCli, WritesAFilePerFrameAndAnIndexTheSameAsRunDoes) {
    writeFile("colliding.json", kCollidingBlocksScene);
    const RunResult run = weir(
        "run colliding.json --backend cpu --quiet --frames 4 --out frames --whitewater "
        "--format ply");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "5 whitewater frames in frames/whitewater/"));

    const RunResult post = weir("whitewater frames --out again --quiet");
    ASSERT_EQ(post.exitCode, 0) << post.output;
    EXPECT_TRUE(contains(post.output, "5 whitewater frames in again/"));
    EXPECT_EQ(entries(dir_ / "again"),
              (std::vector<std::string>{"whitewater.json", "whitewater_00000.ply",
                                        "whitewater_00001.ply", "whitewater_00002.ply",
                                        "whitewater_00003.ply", "whitewater_00004.ply"}));
    const nlohmann::json index = nlohmann::json::parse(fileText(dir_ / "again/whitewater.json"));
    ASSERT_EQ(index["frames"].size(), 5u);
    std::size_t diffuse = 0;
    for (int frame = 0; frame <= 4; ++frame) {
        const std::string name = whitewaterFileName(frame);
        EXPECT_EQ(index["frames"][std::size_t(frame)]["file"], name);
        // The run and the post-process agree to the byte.
        EXPECT_EQ(fileText(dir_ / "frames/whitewater" / name), fileText(dir_ / "again" / name))
            << name;
        const DiffuseParticles p = readWhitewaterPly(path("again/" + name));
        EXPECT_EQ(index["frames"][std::size_t(frame)]["spray"].get<std::size_t>() +
                      index["frames"][std::size_t(frame)]["foam"].get<std::size_t>() +
                      index["frames"][std::size_t(frame)]["bubbles"].get<std::size_t>(),
                  p.size());
        if (frame == 0) {
            EXPECT_EQ(p.size(), 0u) << "nothing is generated before the first interval";
        }
        diffuse += p.size();
    }
    EXPECT_GT(diffuse, 0u) << "colliding blocks make no whitewater";

    // A range starts empty at its first frame.
    const RunResult range = weir("whitewater frames --out part --frames 2:3 --quiet");
    ASSERT_EQ(range.exitCode, 0) << range.output;
    EXPECT_EQ(entries(dir_ / "part"),
              (std::vector<std::string>{"whitewater.json", "whitewater_00002.ply",
                                        "whitewater_00003.ply"}));
    EXPECT_EQ(readWhitewaterPly(path("part/whitewater_00002.ply")).size(), 0u);
}

TEST_F(WhitewaterCli, OverwriteRemovesAnEarlierRunsWhitewater) {
    writeFile("colliding.json", kCollidingBlocksScene);
    ASSERT_EQ(weir("run colliding.json --backend cpu --quiet --frames 2 --out frames --whitewater")
                  .exitCode,
              0);
    ASSERT_EQ(entries(dir_ / "frames" / "whitewater").size(), 4u);
    // A new run in the same folder: the old whitewater would be drawn with the new frames.
    const RunResult again =
        weir("run colliding.json --backend cpu --quiet --frames 2 --out frames --overwrite");
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_TRUE(entries(dir_ / "frames" / "whitewater").empty());
}

#if defined(WEIR_HAS_RENDER)
TEST_F(WhitewaterCli, RenderDrawsTheWhitewaterBesideTheFrames) {
    writeFile("colliding.json", kCollidingBlocksScene);
    ASSERT_EQ(weir("run colliding.json --backend cpu --quiet --frames 3 --out frames --whitewater")
                  .exitCode,
              0);
    const std::string tiny = " --frame 3 --width 48 --height 32 --samples 1 --backend cpu";
    const RunResult water = weir("render frames --look water --out water" + tiny);
    ASSERT_EQ(water.exitCode, 0) << water.output;
    EXPECT_TRUE(contains(water.output, "whitewater from frames/whitewater"));
    const RunResult none = weir("render frames --look water --no-whitewater --out dry" + tiny);
    ASSERT_EQ(none.exitCode, 0) << none.output;
    EXPECT_FALSE(none.output.find("whitewater from") != std::string::npos) << none.output;
    const RunResult missing = weir("render frames --whitewater no_such_folder --out x" + tiny);
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_TRUE(contains(missing.output, "no_such_folder"));
}
#endif

TEST_F(WhitewaterCli, AFolderWithoutFramesIsAClearError) {
    const RunResult missing = weir("whitewater no_such_run");
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_TRUE(contains(missing.output, "no_such_run"));
    EXPECT_TRUE(contains(missing.output, "error"));

    writeFile("colliding.json", kCollidingBlocksScene);
    ASSERT_EQ(weir("run colliding.json --backend cpu --quiet --frames 1 --out frames").exitCode, 0);
    const RunResult badRate = weir("whitewater frames --rate -3");
    EXPECT_EQ(badRate.exitCode, 2) << badRate.output;
    EXPECT_TRUE(contains(badRate.output, "--rate"));
}

}  // namespace
}  // namespace weir
