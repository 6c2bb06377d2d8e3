// `weir view` under Xvfb: the window opens, simulates and draws frames (the last one saved and
// checked), takes keys for every action, prints its statistics line and quits by itself; without
// a display it fails with a clear message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "cli/cli_test_support.h"
#include "render/camera.h"
#include "render/png_image.h"
#include "render/renderer.h"

namespace weir {
namespace {

using namespace cli_testing;

class ViewCli : public Cli {
   protected:
    // `weir view ARGS` in a virtual X server of its own.
    RunResult viewUnderXvfb(const std::string& args) {
        return shell("xvfb-run -a -s '-screen 0 640x480x24' " + quoted(WEIR_BINARY) + " view " +
                     args);
    }
};

TEST_F(ViewCli, DrawsFramesTakesKeysAndQuitsUnderXvfb) {
    if (!onPath("xvfb-run")) {
        GTEST_SKIP() << "xvfb-run is not installed (Debian: apt-get install xvfb xauth)";
    }
    writeFile("tiny.json", kTinyDrawScene);
    // Colour, surface and back, a pause, a single step, a reset, then run on: every key's path.
    const RunResult view = viewUnderXvfb(
        "tiny.json --backend cpu --width 320 --height 200 --max-frames 14 "
        "--press none,none,c,m,none,m,space,s,s,space,r,c,c --screenshot shot.png");
    ASSERT_EQ(view.exitCode, 0) << view.output;
    EXPECT_TRUE(contains(view.output, "144 particles on cpu"));
    EXPECT_TRUE(contains(view.output, "view closed after 14 frames"));
    EXPECT_TRUE(contains(view.output, "144 particles"));
    EXPECT_TRUE(contains(view.output, "steps/s"));
    // Per-stage times of the last step, in ms.
    for (const char* stage : {"grid ", "density ", "force ", "integrate ", "step "}) {
        EXPECT_TRUE(contains(view.output, stage));
    }
    EXPECT_TRUE(contains(view.output, " ms"));
    EXPECT_FALSE(contains(view.output, "BLEW UP"));

    // The last frame: the fluid where the camera frames it, background far from it, the overlay
    // text at the top left, the legend at the right.
    const Image shot = readPng(path("shot.png"));
    ASSERT_EQ(shot.width, 320);
    ASSERT_EQ(shot.height, 200);
    const OrbitCamera camera = frameBox({{0, 0, 0}, {0.3, 0.2, 0.08}}, 320.0 / 200.0);
    const PixelPoint fluid = projectToPixel(camera, Vec3d(0.04, 0.03, 0.08), 320, 200);
    auto isBackground = [&](int x, int y) {
        const std::uint8_t* p = shot.pixel(x, y);
        return std::abs(p[0] - int(std::lround(kBackground.r * 255))) <= 1 &&
               std::abs(p[1] - int(std::lround(kBackground.g * 255))) <= 1 &&
               std::abs(p[2] - int(std::lround(kBackground.b * 255))) <= 1;
    };
    EXPECT_FALSE(isBackground(int(fluid.x), int(fluid.y)));
    const PixelPoint empty = projectToPixel(camera, Vec3d(0.27, 0.17, 0.04), 320, 200);
    EXPECT_TRUE(isBackground(int(empty.x), int(empty.y)));
    std::size_t text = 0;
    for (int y = 0; y < 40; ++y) {
        for (int x = 0; x < 200; ++x) {
            text += shot.pixel(x, y)[0] > 200 && shot.pixel(x, y)[1] > 200;
        }
    }
    EXPECT_GT(text, 100u) << "no overlay text at the top left";
}

TEST_F(ViewCli, WaterLookKeyTracesOnAGpuOrSaysItNeedsOne) {
    if (!onPath("xvfb-run")) {
        GTEST_SKIP() << "xvfb-run is not installed (Debian: apt-get install xvfb xauth)";
    }
    writeFile("tiny.json", kTinyDrawScene);
    // On for three frames (the paths accumulate while paused), off, on again to the end.
    const RunResult view = viewUnderXvfb(
        "tiny.json --backend cpu --width 160 --height 100 --max-frames 8 "
        "--press none,w,space,none,w,w,none,none --screenshot water.png");
    ASSERT_EQ(view.exitCode, 0) << view.output;
    EXPECT_TRUE(contains(view.output, "view closed after 8 frames"));
    if (contains(view.output, "the water look needs a CUDA GPU")) {
        return;  // no GPU here: the status line says so, the viewer goes on
    }
    EXPECT_TRUE(contains(view.output, "water look on")) << view.output;
    EXPECT_FALSE(contains(view.output, "no water look")) << view.output;
    EXPECT_TRUE(contains(view.output, "paths/px")) << view.output;  // the closing stages line
    const Image shot = readPng(path("water.png"));
    ASSERT_EQ(shot.width, 160);
    std::size_t coloured = 0;
    for (int y = 50; y < 100; ++y) {
        for (int x = 0; x < 160; ++x) {
            const std::uint8_t* p = shot.pixel(x, y);
            coloured += std::abs(p[0] - int(std::lround(kBackground.r * 255))) > 8;
        }
    }
    EXPECT_GT(coloured, 1000u) << "the traced image (floor, sky, water) is not in the window";
}

TEST_F(ViewCli, WithoutADisplayItSaysSo) {
    writeFile("tiny.json", kTinyDrawScene);
    const RunResult view = shell("env -u DISPLAY -u WAYLAND_DISPLAY " + quoted(WEIR_BINARY) +
                                 " view tiny.json --backend cpu --max-frames 1");
    EXPECT_EQ(view.exitCode, 1) << view.output;
    EXPECT_TRUE(contains(view.output, "cannot open a window"));
    EXPECT_TRUE(contains(view.output, "weir render"));
}

TEST_F(ViewCli, BadOptionsAreRefused) {
    const RunResult key = weir("view --press space,x --max-frames 1");
    EXPECT_EQ(key.exitCode, 2) << key.output;
    EXPECT_TRUE(contains(key.output, "'x' is not a key"));
    const RunResult shot = weir("view --screenshot a.png");
    EXPECT_EQ(shot.exitCode, 2) << shot.output;
    EXPECT_TRUE(contains(shot.output, "--max-frames"));
    const RunResult help = weir("view --help");
    EXPECT_EQ(help.exitCode, 0);
    for (const char* option : {"--backend", "--max-frames", "--color", "--camera", "pause"}) {
        EXPECT_TRUE(contains(help.output, option));
    }
}

TEST_F(ViewCli, RecordsEveryFrameDrawnIntoAVideo) {
    if (!onPath("xvfb-run") || !onPath("ffmpeg")) {
        GTEST_SKIP() << "needs xvfb-run and ffmpeg (Debian: apt-get install xvfb xauth ffmpeg)";
    }
    writeFile("tiny.json", kTinyDrawScene);
    const RunResult view = viewUnderXvfb(
        "tiny.json --backend cpu --width 160 --height 100 --max-frames 6 --record films/v.mp4");
    ASSERT_EQ(view.exitCode, 0) << view.output;
    EXPECT_TRUE(contains(view.output, "video films/v.mp4: 6 frames"));
    EXPECT_EQ(entries(dir_ / "films"), std::vector<std::string>{"v.mp4"});  // no temporary left
    const std::string video = fileText(dir_ / "films/v.mp4");
    ASSERT_GT(video.size(), 500u);
    EXPECT_EQ(video.substr(4, 4), "ftyp");
    const RunResult probe = shell(
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=width,height,nb_read_frames -of csv=p=0 films/v.mp4");
    if (probe.exitCode == 0) {
        EXPECT_TRUE(contains(probe.output, "160,100,6")) << probe.output;
    }
}

TEST_F(ViewCli, RecordFailsClearlyWithoutFfmpegBeforeAnyWindow) {
    writeFile("tiny.json", kTinyDrawScene);
    const RunResult noFfmpeg = shell("env PATH=/nonexistent " + quoted(WEIR_BINARY) +
                                     " view tiny.json --backend cpu --record v.mp4");
    EXPECT_EQ(noFfmpeg.exitCode, 1) << noFfmpeg.output;
    EXPECT_TRUE(contains(noFfmpeg.output, "--record needs ffmpeg on PATH"));
    EXPECT_FALSE(contains(noFfmpeg.output, "cannot open a window")) << noFfmpeg.output;
    const RunResult extension = weir("view tiny.json --record v.avi");
    EXPECT_EQ(extension.exitCode, 2) << extension.output;
    EXPECT_TRUE(contains(extension.output, "--record 'v.avi': the file name must end in .mp4"));
}

}  // namespace
}  // namespace weir
