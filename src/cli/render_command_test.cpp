// End-to-end tests of `weir render` and `weir run --render` under EGL (Mesa's software renderer
// where there is no GPU): one PNG per frame, fluid pixels where the particles project, background
// elsewhere, colours from the map; surface images; bad options refused with the value.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_test_support.h"
#include "io/frame_reader.h"
#include "render/camera.h"
#include "render/colour_map.h"
#include "render/png_image.h"
#include "render/renderer.h"

namespace weir {
namespace {

using namespace cli_testing;
using Json = nlohmann::json;

constexpr int kWidth = 320;
constexpr int kHeight = 200;

class RenderCli : public Cli {};

int difference(const std::uint8_t* pixel, const Rgb& c) {
    const float want[3] = {c.r, c.g, c.b};
    int worst = 0;
    for (int k = 0; k < 3; ++k) {
        worst = std::max(worst, std::abs(int(pixel[k]) - int(std::lround(want[k] * 255))));
    }
    return worst;
}

// The smallest difference between a pixel and the lit colour map's shades at t = 0 .. 1: near 0
// for a sprite's centre.
// How far (in 8-bit steps) a pixel is from every shade the particle shader can give a colour of
// the map: base(t) * light + highlight, light in [ambient, ambient + diffuse], highlight in
// [0, specular] added to each channel alike.
int distanceToShadedMap(const std::uint8_t* pixel) {
    const ParticleLighting lighting;
    double best = 255;
    for (int i = 0; i <= 255; ++i) {
        const Rgb c = viridis(i / 255.0);
        const double base[3] = {c.r * 255.0, c.g * 255.0, c.b * 255.0};
        for (int l = 0; l <= 60; ++l) {
            const double light = lighting.ambient + lighting.diffuse * l / 60.0;
            double residual[3], mean = 0;
            for (int k = 0; k < 3; ++k) {
                residual[k] = pixel[k] - base[k] * light;
                mean += residual[k] / 3;
            }
            const double highlight = std::clamp(mean, 0.0, 255.0 * lighting.specular);
            double worst = 0;
            for (int k = 0; k < 3; ++k) {
                worst = std::max(worst, std::abs(residual[k] - highlight));
            }
            best = std::min(best, worst);
        }
    }
    return int(std::lround(best));
}

// Checks one image of particles against where the camera projects them: a pixel at each
// particle's centre that is not background, background far from every particle (the container's
// lines and the legend aside), and the particles nearest the camera coloured from the map.
void expectParticlesWhereTheyProject(const Image& image, const HostParticles& p,
                                     const OrbitCamera& camera, double radius,
                                     const PixelRect& keepOut, bool checkMapColour) {
    std::vector<PixelPoint> centres;
    std::vector<double> radii;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3d x(p.x[i], p.y[i], p.z[i]);
        centres.push_back(projectToPixel(camera, x, image.width, image.height));
        radii.push_back(projectedRadius(camera, x, radius, image.height));
        const int px = int(centres.back().x), py = int(centres.back().y);
        ASSERT_TRUE(px >= 0 && px < image.width && py >= 0 && py < image.height)
            << "particle " << i;
        EXPECT_GT(difference(image.pixel(px, py), kBackground), 3)
            << "particle " << i << " pixel " << px << "," << py << ": "
            << int(image.pixel(px, py)[0]) << " " << int(image.pixel(px, py)[1]) << " "
            << int(image.pixel(px, py)[2]);
    }
    if (checkMapColour) {
        // A particle whose centre no nearer particle covers shows a colour of the map there, as
        // the shader lights it; the container's front edges cross a few.
        std::size_t visible = 0, mapColoured = 0;
        for (std::size_t i = 0; i < p.size(); ++i) {
            bool covered = false;
            for (std::size_t j = 0; j < p.size() && !covered; ++j) {
                covered = j != i && centres[j].depth < centres[i].depth &&
                          std::hypot(centres[j].x - centres[i].x, centres[j].y - centres[i].y) <
                              radii[j] + 1;
            }
            if (!covered) {
                ++visible;
                mapColoured +=
                    distanceToShadedMap(image.pixel(int(centres[i].x), int(centres[i].y))) <= 6;
            }
        }
        EXPECT_GT(visible, p.size() / 10);
        EXPECT_GE(double(mapColoured), 0.9 * double(visible))
            << mapColoured << " of " << visible << " visible particles";
    }
    std::size_t background = 0, notBackground = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            if (x >= keepOut.left && x < keepOut.right && y >= keepOut.top && y < keepOut.bottom) {
                continue;
            }
            double nearest = INFINITY;
            for (std::size_t i = 0; i < centres.size(); ++i) {
                nearest = std::min(
                    nearest, std::hypot(x + 0.5 - centres[i].x, y + 0.5 - centres[i].y) - radii[i]);
            }
            if (nearest > 3) {
                const bool isBackground = difference(image.pixel(x, y), kBackground) <= 1;
                background += isBackground;
                notBackground += !isBackground;
            }
        }
    }
    // Far from the particles, only the container's thin edges and the text differ.
    EXPECT_GT(background, 0u);
    EXPECT_LT(double(notBackground), 0.06 * double(background + notBackground))
        << notBackground << " pixels away from all particles are not background";
}

TEST_F(RenderCli, RunRenderWritesOneImagePerFrameShowingTheParticles) {
    writeFile("tiny.json", kTinyDrawScene);
    const RunResult run = weir(
        "run tiny.json --backend cpu --quiet --frames 2 --out frames "
        "--render --width 320 --height 200 --samples 1");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "3 images in frames/images/"));
    EXPECT_EQ(entries(dir_ / "frames" / "images"),
              (std::vector<std::string>{"frame_00000.png", "frame_00001.png", "frame_00002.png"}));
    // The camera `weir run --render` uses: framed on the container.
    const Box container{{0, 0, 0}, {0.3, 0.2, 0.08}};
    const OrbitCamera camera = frameBox(container, double(kWidth) / kHeight);
    const PixelRect legend = legendBarRect(kWidth, kHeight);
    // Legend bar, its labels and title on the right; the overlay text is off for images.
    const PixelRect keepOut{legend.left - 60, legend.top - 30, kWidth, legend.bottom + 20};
    for (int frame = 0; frame <= 2; ++frame) {
        const std::string name = "frame_0000" + std::to_string(frame);
        const Image image = readPng(path("frames/images/" + name + ".png"));
        ASSERT_EQ(image.width, kWidth);
        ASSERT_EQ(image.height, kHeight);
        const HostParticles particles = readVtu(path("frames/" + name + ".vtu"));
        SCOPED_TRACE(name);
        expectParticlesWhereTheyProject(image, particles, camera, 0.01, keepOut, true);
    }
    // Frame 0 is at rest: speed 0 everywhere, the bottom of the map, so the particles facing the
    // camera show viridis(0) lit.
    const Image first = readPng(path("frames/images/frame_00000.png"));
    const HostParticles p0 = readVtu(path("frames/frame_00000.vtu"));
    std::size_t darkPurple = 0;
    for (std::size_t i = 0; i < p0.size(); ++i) {
        const PixelPoint c =
            projectToPixel(camera, Vec3d(p0.x[i], p0.y[i], p0.z[i]), kWidth, kHeight);
        darkPurple +=
            difference(first.pixel(int(c.x), int(c.y)), particleCentreColour(viridis(0))) <= 10;
    }
    EXPECT_GT(darkPurple, p0.size() / 2);
}

TEST_F(RenderCli, RenderCommandUsesTheCameraAndColouringOfItsFlags) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 3 --out frames").exitCode, 0);
    const RunResult render = weir(
        "render frames --width 320 --height 200 --samples 1 --scene tiny.json "
        "--camera -30,35,0.9 --target 0.1,0.05,0.04 --color density --out pictures");
    ASSERT_EQ(render.exitCode, 0) << render.output;
    EXPECT_TRUE(contains(render.output, "4 images in pictures/"));
    EXPECT_TRUE(contains(render.output, "density"));
    OrbitCamera camera;
    camera.yaw = -30;
    camera.pitch = 35;
    camera.distance = 0.9;
    camera.target = Vec3d(0.1, 0.05, 0.04);
    const PixelRect legend = legendBarRect(kWidth, kHeight);
    const PixelRect keepOut{legend.left - 70, legend.top - 30, kWidth, legend.bottom + 20};
    for (int frame : {0, 3}) {
        const std::string name = "frame_0000" + std::to_string(frame);
        const Image image = readPng(path("pictures/" + name + ".png"));
        const HostParticles particles = readVtu(path("frames/" + name + ".vtu"));
        SCOPED_TRACE(name);
        expectParticlesWhereTheyProject(image, particles, camera, 0.01, keepOut, true);
    }
    // The legend bar runs through the map from bottom to top.
    const Image image = readPng(path("pictures/frame_00000.png"));
    const int x = (legend.left + legend.right) / 2;
    EXPECT_LE(difference(image.pixel(x, legend.bottom - 2), viridis(0)), 10);
    EXPECT_LE(difference(image.pixel(x, legend.top + 1), viridis(1)), 10);
}

TEST_F(RenderCli, RenderSurfaceDrawsWaterOverTheFluid) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 0 --out frames").exitCode, 0);
    const RunResult render = weir(
        "render frames --surface --width 320 --height 200 --samples 1 --scene tiny.json "
        "--backend cpu --quiet");
    ASSERT_EQ(render.exitCode, 0) << render.output;
    EXPECT_TRUE(contains(render.output, "ms per surface on cpu"));
    const Image image = readPng(path("frames/images/frame_00000.png"));
    const OrbitCamera camera = frameBox({{0, 0, 0}, {0.3, 0.2, 0.08}}, double(kWidth) / kHeight);
    // The centre of the block's front face is water: blue above red and green.
    const PixelPoint face = projectToPixel(camera, Vec3d(0.06, 0.06, 0.08), kWidth, kHeight);
    const std::uint8_t* px = image.pixel(int(face.x), int(face.y));
    EXPECT_GT(px[2], px[0] + 40) << int(px[0]) << " " << int(px[1]) << " " << int(px[2]);
    EXPECT_GT(px[2], px[1]);
    // The far end of the container holds no fluid: background there (off the container edges).
    const PixelPoint empty = projectToPixel(camera, Vec3d(0.25, 0.1, 0.04), kWidth, kHeight);
    EXPECT_LE(difference(image.pixel(int(empty.x), int(empty.y)), kBackground), 1);
}

TEST_F(RenderCli, ParticleSpacingComesFromTheSceneForAnyFirstFrame) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 8 --out frames").exitCode, 0);
    // Keep only the last frame in the index: the fluid has moved, its particles no longer sit on
    // the 2 cm lattice.
    Json index = Json::parse(fileText(dir_ / "frames" / "frames.json"));
    index["frames"] = Json::array({index["frames"].back()});
    writeFile("frames/frames.json", index.dump());
    const RunResult withScene =
        weir("render frames --width 64 --height 48 --samples 1 --scene tiny.json");
    ASSERT_EQ(withScene.exitCode, 0) << withScene.output;
    EXPECT_TRUE(contains(withScene.output, "particle spacing 0.02 m"));
    const RunResult given =
        weir("render frames --width 64 --height 48 --samples 1 --spacing 0.025");
    ASSERT_EQ(given.exitCode, 0) << given.output;
    EXPECT_TRUE(contains(given.output, "particle spacing 0.025 m"));
}

TEST_F(RenderCli, VideoIsEncodedWithFfmpeg) {
    if (!onPath("ffmpeg")) {
        GTEST_SKIP() << "ffmpeg is not installed (Debian: apt-get install ffmpeg)";
    }
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 4 --out frames").exitCode, 0);
    const RunResult render =
        weir("render frames --width 160 --height 100 --samples 1 --quiet --video films/tiny.mp4");
    ASSERT_EQ(render.exitCode, 0) << render.output;
    EXPECT_TRUE(contains(render.output, "video films/tiny.mp4 (H.264, 30 frames/s)"));
    // An MP4 (an 'ftyp' box first) and nothing else in its directory: the temporary is renamed.
    EXPECT_EQ(entries(dir_ / "films"), std::vector<std::string>{"tiny.mp4"});
    const std::string video = fileText(dir_ / "films" / "tiny.mp4");
    ASSERT_GT(video.size(), 1000u);
    EXPECT_EQ(video.substr(4, 4), "ftyp");
    // ffmpeg reads it back as 5 frames of 160 x 100.
    const RunResult probe = shell(
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=width,height,nb_read_frames -of csv=p=0 films/tiny.mp4");
    if (probe.exitCode == 0) {
        EXPECT_TRUE(contains(probe.output, "160,100,5")) << probe.output;
    }
}

TEST_F(RenderCli, BadInputIsRefusedWithTheValue) {
    const RunResult missing = weir("render nowhere");
    EXPECT_EQ(missing.exitCode, 1) << missing.output;
    EXPECT_TRUE(contains(missing.output, "'nowhere'"));

    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 0 --out frames").exitCode, 0);
    const RunResult colour = weir("render frames --color temperature");
    EXPECT_EQ(colour.exitCode, 2) << colour.output;
    EXPECT_TRUE(contains(colour.output, "temperature"));
    EXPECT_TRUE(contains(colour.output, "speed"));

    const RunResult camera = weir("render frames --camera 10,95,1");
    EXPECT_EQ(camera.exitCode, 2) << camera.output;
    EXPECT_TRUE(contains(camera.output, "--camera '10,95,1'"));

    const RunResult video = weir("render frames --video film.avi");
    EXPECT_EQ(video.exitCode, 2) << video.output;
    EXPECT_TRUE(contains(video.output, "film.avi"));
    EXPECT_TRUE(contains(video.output, ".mp4"));

    const RunResult size = weir("render frames --width 8");
    EXPECT_EQ(size.exitCode, 2) << size.output;
    EXPECT_TRUE(contains(size.output, "--width"));

    const RunResult surfaceOnly = weir("run tiny.json --frames 0 --surface");
    EXPECT_EQ(surfaceOnly.exitCode, 2) << surfaceOnly.output;
    EXPECT_TRUE(contains(surfaceOnly.output, "--render"));

    EXPECT_FALSE(fs::exists(dir_ / "frames" / "images" / "frame_00000.png"));

    const RunResult help = weir("render --help");
    EXPECT_EQ(help.exitCode, 0);
    for (const char* option : {"--width", "--height", "--color", "--camera", "--target", "--scene",
                               "--surface", "--video"}) {
        EXPECT_TRUE(contains(help.output, option));
    }
}

// --- the water look (issue 19) -------------------------------------------------------------

// Red over green in a square of pixels about a point: how much of the red the water has taken.
double redOverGreen(const Image& image, const PixelPoint& at, int half) {
    double red = 0, green = 0;
    for (int y = int(at.y) - half; y <= int(at.y) + half; ++y) {
        for (int x = int(at.x) - half; x <= int(at.x) + half; ++x) {
            red += image.pixel(x, y)[0];
            green += image.pixel(x, y)[1];
        }
    }
    return red / green;
}

TEST_F(RenderCli, WaterLookTracesTheSurfaceWithoutOpenGl) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 0 --out frames").exitCode, 0);
    // No EGL vendor library: the preview look cannot draw, the water look needs none.
    const std::string noEgl = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json ";
    const RunResult preview =
        shell(noEgl + quoted(WEIR_BINARY) + " render frames --width 64 --height 48 --out none");
    EXPECT_EQ(preview.exitCode, 1) << preview.output;
    const RunResult water = shell(noEgl + quoted(WEIR_BINARY) +
                                  " render frames --look water --width 160 --height 100 "
                                  "--samples 16 --backend cpu --out water");
    ASSERT_EQ(water.exitCode, 0) << water.output;
    EXPECT_TRUE(contains(water.output, "water look"));
    EXPECT_TRUE(contains(water.output, "16 paths per pixel"));
    const Image image = readPng(path("water/frame_00000.png"));
    ASSERT_EQ(image.width, 160);
    ASSERT_EQ(image.height, 100);
    // The preview's camera: the block of water (12 x 12 x 8 cm against the far wall, z = 0) is
    // where the preview draws it. Through its front face the camera sees the far wall through 8
    // cm of water, lit through the water too: less red against green than the same wall above
    // the water (Beer-Lambert, red absorbed 5x faster than green).
    const OrbitCamera camera = frameBox({{0, 0, 0}, {0.3, 0.2, 0.08}}, 160.0 / 100.0);
    const PixelPoint throughWater = projectToPixel(camera, Vec3d(0.06, 0.05, 0.08), 160, 100);
    const PixelPoint dryWall = projectToPixel(camera, Vec3d(0.06, 0.175, 0.0), 160, 100);
    const double wet = redOverGreen(image, throughWater, 2), dry = redOverGreen(image, dryWall, 2);
    EXPECT_LT(wet, 0.95 * dry) << "red/green through the water " << wet << ", above it " << dry;
    // The random numbers are a function of pixel and sample: the same image again.
    ASSERT_EQ(weir("render frames --look water --width 160 --height 100 --samples 16 "
                   "--backend cpu --quiet --out again")
                  .exitCode,
              0);
    EXPECT_EQ(fileText(dir_ / "water/frame_00000.png"), fileText(dir_ / "again/frame_00000.png"));
}

TEST_F(RenderCli, WaterLookRefusesBadValuesNamingTheOption) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 0 --out frames").exitCode, 0);
    const RunResult look = weir("render frames --look glass");
    EXPECT_EQ(look.exitCode, 2) << look.output;
    EXPECT_TRUE(contains(look.output, "--look"));
    EXPECT_TRUE(contains(look.output, "glass"));
    EXPECT_TRUE(contains(look.output, "preview,water"));
    // --samples counts paths per pixel for the water look (up to 65536), multisampling for the
    // preview (up to 16).
    const RunResult tooMany = weir("render frames --look water --samples 70000");
    EXPECT_EQ(tooMany.exitCode, 2) << tooMany.output;
    EXPECT_TRUE(contains(tooMany.output, "--samples"));
    EXPECT_TRUE(contains(tooMany.output, "70000"));
    const RunResult none = weir("render frames --look water --samples 0");
    EXPECT_EQ(none.exitCode, 2) << none.output;
    EXPECT_TRUE(contains(none.output, "--samples"));
    const RunResult preview = weir("render frames --samples 64");
    EXPECT_EQ(preview.exitCode, 2) << preview.output;
    EXPECT_TRUE(contains(preview.output, "--samples 64 must be within 1..16 for the preview look"));
    const RunResult run = weir("run tiny.json --frames 0 --out again --render --samples 17");
    EXPECT_EQ(run.exitCode, 2) << run.output;
    EXPECT_TRUE(contains(run.output, "--samples 17 must be within 1..16"));
    const RunResult backend = weir("render frames --look water --backend gpu");
    EXPECT_EQ(backend.exitCode, 2) << backend.output;
    EXPECT_TRUE(contains(backend.output, "gpu"));
    EXPECT_FALSE(fs::exists(dir_ / "frames" / "images"));
    const RunResult help = weir("render --help");
    EXPECT_TRUE(contains(help.output, "--look"));
}

TEST_F(RenderCli, MotionBlurSmearsTheMovingSurfaceOnly) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 3 --out frames").exitCode, 0);
    const std::string water =
        "render frames --look water --width 96 --height 64 --samples 16 --backend cpu --quiet ";
    auto levelsApart = [&](const std::string& a, const std::string& b, int above) {
        const Image x = readPng(path(a)), y = readPng(path(b));
        EXPECT_EQ(x.rgb.size(), y.rgb.size());
        int worst = 0;
        std::size_t count = 0;
        for (std::size_t i = 0; i < std::min(x.rgb.size(), y.rgb.size()); ++i) {
            const int d = std::abs(int(x.rgb[i]) - int(y.rgb[i]));
            worst = std::max(worst, d);
            count += d > above;
        }
        return std::make_pair(worst, count);
    };
    // Frame 0 is the fluid at rest as seeded: every time slice sees the same surface, and the
    // slices' consecutive shares of the paths make the sharp image (up to float rounding).
    ASSERT_EQ(weir(water + "--frame 0 --out sharp").exitCode, 0);
    const RunResult blurred = weir(water + "--frame 0 --motion-blur 1 --out blurred");
    ASSERT_EQ(blurred.exitCode, 0) << blurred.output;
    EXPECT_LE(levelsApart("sharp/frame_00000.png", "blurred/frame_00000.png", 1).first, 1);
    // Frame 3: the column is slumping; a shutter open for a whole frame (33 ms) changes the image
    // where the surface moves.
    ASSERT_EQ(weir(water + "--frame 3 --out sharp").exitCode, 0);
    ASSERT_EQ(weir(water + "--frame 3 --motion-blur 1 --out blurred").exitCode, 0);
    const auto [worst, changed] =
        levelsApart("sharp/frame_00003.png", "blurred/frame_00003.png", 6);
    EXPECT_GT(worst, 20);
    EXPECT_GT(changed, 50u);
    // Refused, naming the option: a share outside [0, 1], the preview look, --export-water.
    const RunResult share = weir("render frames --look water --motion-blur 1.5");
    EXPECT_EQ(share.exitCode, 2) << share.output;
    EXPECT_TRUE(contains(share.output, "--motion-blur"));
    const RunResult preview = weir("render frames --motion-blur 0.5");
    EXPECT_EQ(preview.exitCode, 2) << preview.output;
    EXPECT_TRUE(contains(preview.output, "--motion-blur blurs the water look"));
    const RunResult exported =
        weir("render frames --look water --motion-blur 0.5 --export-water exported");
    EXPECT_EQ(exported.exitCode, 2) << exported.output;
    EXPECT_TRUE(contains(exported.output, "use one of them"));
}

// --- the artists' loop (issue 20) ---------------------------------------------------------

TEST_F(RenderCli, RenderNeedsNoSceneAsFramesJsonRecordsIt) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 2 --out frames").exitCode, 0);
    const RunResult recorded =
        weir("render frames --width 96 --height 64 --samples 1 --quiet --out recorded");
    ASSERT_EQ(recorded.exitCode, 0) << recorded.output;
    const RunResult given =
        weir("render frames --width 96 --height 64 --samples 1 --scene tiny.json --out given");
    ASSERT_EQ(given.exitCode, 0) << given.output;
    EXPECT_TRUE(contains(given.output, "scene tiny (--scene)"));
    // The same container, camera and spacing: the same pictures.
    for (const char* image : {"frame_00000.png", "frame_00002.png"}) {
        EXPECT_EQ(fileText(dir_ / "recorded" / image), fileText(dir_ / "given" / image)) << image;
    }
    const RunResult loud = weir("render frames --width 96 --height 64 --samples 1 --out loud");
    ASSERT_EQ(loud.exitCode, 0) << loud.output;
    EXPECT_TRUE(contains(loud.output, "scene tiny (from frames.json)"));
    EXPECT_TRUE(contains(loud.output, "particle spacing 0.02 m"));

    // --scene still overrides: another container frames the camera differently.
    std::string wide = kTinyDrawScene;
    wide.replace(wide.find("[0.3, 0.2, 0.08]"), 16, "[0.6, 0.4, 0.16]");
    writeFile("wide.json", wide);
    const RunResult other = weir(
        "render frames --width 96 --height 64 --samples 1 --quiet --scene wide.json --out wide");
    ASSERT_EQ(other.exitCode, 0) << other.output;
    EXPECT_NE(fileText(dir_ / "wide/frame_00000.png"), fileText(dir_ / "given/frame_00000.png"));
}

TEST_F(RenderCli, RenderAndMeshTakeOneFrameOrARange) {
    writeFile("tiny.json", kTinyDrawScene);
    ASSERT_EQ(weir("run tiny.json --backend cpu --quiet --frames 3 --out frames").exitCode, 0);
    const RunResult one = weir("render frames --width 64 --height 48 --samples 1 --frame 2");
    ASSERT_EQ(one.exitCode, 0) << one.output;
    EXPECT_EQ(entries(dir_ / "frames/images"), std::vector<std::string>{"frame_00002.png"});
    const RunResult range =
        weir("render frames --width 64 --height 48 --samples 1 --frames 1:2 --out range");
    ASSERT_EQ(range.exitCode, 0) << range.output;
    EXPECT_EQ(entries(dir_ / "range"),
              (std::vector<std::string>{"frame_00001.png", "frame_00002.png"}));
    const RunResult tail = weir("mesh frames --format obj --frames 2:");
    ASSERT_EQ(tail.exitCode, 0) << tail.output;
    EXPECT_EQ(entries(dir_ / "frames/mesh"),
              (std::vector<std::string>{"surface_00002.obj", "surface_00003.obj"}));
    const RunResult head = weir("mesh frames --format ply --frame 0 --out head");
    ASSERT_EQ(head.exitCode, 0) << head.output;
    EXPECT_EQ(entries(dir_ / "head"), std::vector<std::string>{"surface_00000.ply"});

    const RunResult none = weir("render frames --frames 5:9");
    EXPECT_EQ(none.exitCode, 2) << none.output;
    EXPECT_TRUE(contains(none.output, "--frames 5:9 selects no frame"));
    EXPECT_TRUE(contains(none.output, "frames 0 to 3"));
    const RunResult malformed = weir("mesh frames --frames 2-3");
    EXPECT_EQ(malformed.exitCode, 2) << malformed.output;
    EXPECT_TRUE(contains(malformed.output, "--frames 2-3: write A:B"));
    const RunResult both = weir("render frames --frame 1 --frames 1:2");
    EXPECT_EQ(both.exitCode, 2) << both.output;
    const RunResult backwards = weir("mesh frames --frames 3:1");
    EXPECT_EQ(backwards.exitCode, 2) << backwards.output;
    EXPECT_TRUE(contains(backwards.output, "after the last"));
}

}  // namespace
}  // namespace weir
