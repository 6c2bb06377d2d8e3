// Offscreen rendering through EGL (Mesa's llvmpipe on machines without a GPU): particles land
// where the camera projects them, shaded through the colour map, nearer ones in front; background
// everywhere else; the legend shows the map; a surface is drawn as water; PNG files round-trip.
#include "render/renderer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <memory>

#include "io/io_error.h"
#include "render/egl_context.h"
#include "surface/surface.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 240;

// Colour distance in 8-bit steps (the largest channel difference).
int difference(const std::uint8_t* pixel, const Rgb& c) {
    const float want[3] = {c.r, c.g, c.b};
    int worst = 0;
    for (int k = 0; k < 3; ++k) {
        const int expected = int(std::lround(std::clamp(want[k], 0.0f, 1.0f) * 255));
        worst = std::max(worst, std::abs(int(pixel[k]) - expected));
    }
    return worst;
}

// The mean of the 2 x 2 pixels around a point of the image: a sphere's shade at its centre, to
// first order, wherever the centre falls between pixels.
std::array<std::uint8_t, 3> centreShade(const Image& image, double x, double y) {
    const int x0 = int(std::floor(x - 0.5)), y0 = int(std::floor(y - 0.5));
    std::array<std::uint8_t, 3> mean{};
    for (int k = 0; k < 3; ++k) {
        int sum = 0;
        for (int dy = 0; dy < 2; ++dy) {
            for (int dx = 0; dx < 2; ++dx) {
                sum += image.pixel(x0 + dx, y0 + dy)[k];
            }
        }
        mean[std::size_t(k)] = std::uint8_t((sum + 2) / 4);
    }
    return mean;
}

// One EGL context for every test of the suite: making one costs Mesa a few tens of ms.
class OffscreenRender : public ::testing::Test {
   protected:
    static void SetUpTestSuite() { context_ = std::make_unique<OffscreenContext>(); }
    static void TearDownTestSuite() { context_.reset(); }
    void SetUp() override {
        context_->makeCurrent();
        renderer_ = std::make_unique<Renderer>();
        renderer_->setSamples(1);
    }
    void TearDown() override { renderer_.reset(); }

    // The scene's one body posed at the origin, turned a quarter turn about z, seen by camera.
    Image renderUpright(const SceneGeometry& geometry, const OrbitCamera& camera) {
        renderer_->setGeometry(geometry);
        renderer_->setShowLegend(false);
        BodyPose pose;
        const double half = 0.5 * 1.5707963267948966;
        pose.orientation[2] = std::sin(half);
        pose.orientation[3] = std::cos(half);
        renderer_->setBodies(geometry.bodies, {pose});
        return renderer_->renderImage(camera, kWidth, kHeight);
    }

    static std::unique_ptr<OffscreenContext> context_;
    std::unique_ptr<Renderer> renderer_;
};
std::unique_ptr<OffscreenContext> OffscreenRender::context_;

// Particles on a 3 x 3 grid in the z = 0 plane, far enough apart not to touch on screen, with
// speeds 0, 1/8, ..., 1 so that each shows a different colour of the map.
HostParticles speedGrid(double gap) {
    HostParticles p;
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
            const double speed = double(j * 3 + i) / 8.0;
            p.push(Vec3d((i - 1) * gap, (j - 1) * gap, 0), Vec3d(speed, 0, 0));
        }
    }
    return p;
}

OrbitCamera frontCamera() {
    OrbitCamera camera;
    camera.yaw = 0;
    camera.pitch = 0;
    camera.distance = 2;
    camera.target = Vec3d(0, 0, 0);
    return camera;
}

TEST_F(OffscreenRender, ContextIsOpenGl33Core) {
    EXPECT_NE(context_->description().find("OpenGL"), std::string::npos) << context_->description();
}

TEST_F(OffscreenRender, ParticlesLandWhereTheyProjectInTheirMapColour) {
    const double radius = 0.06, gap = 0.3;
    const HostParticles particles = speedGrid(gap);
    renderer_->setShowLegend(false);
    renderer_->setParticles(particles, ColourField::Speed, radius);
    renderer_->setColourRange({0, 1});
    // A camera off the axis, so that the projection is not trivially symmetric.
    OrbitCamera camera = frontCamera();
    camera.yaw = 20;
    camera.pitch = 15;
    const Image image = renderer_->renderImage(camera, kWidth, kHeight);
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);

    std::vector<PixelPoint> centres;
    std::vector<double> radii;
    for (std::size_t i = 0; i < particles.size(); ++i) {
        const Vec3d x(particles.x[i], particles.y[i], particles.z[i]);
        centres.push_back(projectToPixel(camera, x, kWidth, kHeight));
        radii.push_back(projectedRadius(camera, x, radius, kHeight));
        ASSERT_TRUE(centres.back().inFront);
        ASSERT_GT(radii.back(), 5) << "particles too small on screen to test";
        // The centre of each sprite faces the viewer: the map colour at its speed, lit.
        const int px = int(centres.back().x), py = int(centres.back().y);
        ASSERT_TRUE(px >= 0 && px < kWidth && py >= 0 && py < kHeight);
        const Rgb expected = particleCentreColour(viridis(double(i) / 8.0));
        const auto shade = centreShade(image, centres.back().x, centres.back().y);
        const std::uint8_t* got = shade.data();
        // Within 8 steps: the mean of pixels beside the centre reads a little brighter than the
        // centre itself, as the sharp highlight is convex there; neighbouring map colours
        // (1/8 of the map apart) differ by 20 steps or more.
        EXPECT_LE(difference(got, expected), 8)
            << "particle " << i << " at pixel " << px << "," << py << " (" << centres.back().x
            << "," << centres.back().y << ") got " << int(got[0]) << " " << int(got[1]) << " "
            << int(got[2]) << " expected " << expected.r * 255 << " " << expected.g * 255 << " "
            << expected.b * 255;
    }
    // The nine centres show nine different colours: the map is applied, not one flat colour.
    for (std::size_t i = 1; i < centres.size(); ++i) {
        const std::uint8_t* a = image.pixel(int(centres[i].x), int(centres[i].y));
        const std::uint8_t* b = image.pixel(int(centres[i - 1].x), int(centres[i - 1].y));
        EXPECT_GT(std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]), 6)
            << "particles " << i - 1 << " and " << i;
    }
    // Every pixel inside a sprite (away from its rim) is fluid; every pixel clear of all sprites
    // is background.
    std::size_t fluid = 0, background = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            double nearest = INFINITY;  // in sprite radii
            for (std::size_t i = 0; i < centres.size(); ++i) {
                const double dx = x + 0.5 - centres[i].x, dy = y + 0.5 - centres[i].y;
                nearest = std::min(nearest, std::sqrt(dx * dx + dy * dy) / radii[i]);
            }
            const bool isBackground = difference(image.pixel(x, y), kBackground) <= 1;
            if (nearest < 0.8) {
                EXPECT_FALSE(isBackground) << "pixel " << x << "," << y << " inside a sprite";
                ++fluid;
            } else if (nearest > 1.2) {
                EXPECT_TRUE(isBackground) << "pixel " << x << "," << y << " outside every sprite";
                ++background;
            }
        }
    }
    EXPECT_GT(fluid, 9u * 50u);
    EXPECT_GT(background, std::size_t(kWidth * kHeight / 2));
}

TEST_F(OffscreenRender, NearerParticleHidesTheOneBehind) {
    HostParticles p;
    p.push(Vec3d(0, 0, -0.2), Vec3d(0, 0, 0));  // far, slow: dark purple
    p.push(Vec3d(0, 0, 0.2), Vec3d(1, 0, 0));   // near, fast: yellow
    renderer_->setShowLegend(false);
    renderer_->setParticles(p, ColourField::Speed, 0.05);
    renderer_->setColourRange({0, 1});
    const OrbitCamera camera = frontCamera();
    const Image image = renderer_->renderImage(camera, kWidth, kHeight);
    EXPECT_LE(difference(centreShade(image, kWidth / 2, kHeight / 2).data(),
                         particleCentreColour(viridis(1))),
              4);

    // Drawn in the other order, the result is the same: depth, not drawing order, decides.
    HostParticles reversed;
    reversed.push(Vec3d(0, 0, 0.2), Vec3d(1, 0, 0));
    reversed.push(Vec3d(0, 0, -0.2), Vec3d(0, 0, 0));
    renderer_->setParticles(reversed, ColourField::Speed, 0.05);
    const Image again = renderer_->renderImage(camera, kWidth, kHeight);
    EXPECT_LE(difference(centreShade(again, kWidth / 2, kHeight / 2).data(),
                         particleCentreColour(viridis(1))),
              4);
}

TEST_F(OffscreenRender, LegendShowsTheColourMapFromLowToHigh) {
    renderer_->setParticles(speedGrid(0.3), ColourField::Speed, 0.02);
    renderer_->setColourRange({0, 2});
    const Image image = renderer_->renderImage(frontCamera(), kWidth, kHeight);
    const PixelRect bar = legendBarRect(kWidth, kHeight);
    const int x = (bar.left + bar.right) / 2;
    for (double t : {0.05, 0.25, 0.5, 0.75, 0.95}) {
        // Row of value t: bottom row is lo, top row is hi.
        const int y = int(bar.bottom - 1 - t * (bar.bottom - 1 - bar.top));
        EXPECT_LE(difference(image.pixel(x, y), viridis(t)), 8) << "t " << t << " row " << y;
    }
    // Labels: some pixels left of the bar are text-coloured (the range's numbers).
    std::size_t lit = 0;
    for (int y = bar.top - 20; y < bar.bottom + 20; ++y) {
        for (int xx = 0; xx < bar.left - 2; ++xx) {
            lit += image.pixel(xx, y)[0] > 200 && image.pixel(xx, y)[1] > 200;
        }
    }
    EXPECT_GT(lit, 20u);
}

TEST_F(OffscreenRender, SurfaceIsDrawnAsWaterWithinItsOutline) {
    const double d = 0.02, ballRadius = 0.25;
    const HostParticles ball = testing::latticeBall(Vec3d(0, 0, 0), ballRadius, d);
    SurfaceOptions options;
    options.spacing = d;
    const TriangleMesh mesh = reconstructSurface(Backend::Cpu, ball, options);
    ASSERT_GT(mesh.triangleCount(), 100u);
    renderer_->setMesh(mesh);
    renderer_->setParticles(ball, ColourField::Speed, d / 2);
    renderer_->setMode(RenderMode::Surface);
    const OrbitCamera camera = frontCamera();
    const Image image = renderer_->renderImage(camera, kWidth, kHeight);
    const PixelPoint centre = projectToPixel(camera, Vec3d(0, 0, 0), kWidth, kHeight);
    const double outline = projectedRadius(camera, Vec3d(0, 0, 0), ballRadius, kHeight);
    std::size_t water = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const double r = std::hypot(x + 0.5 - centre.x, y + 0.5 - centre.y) / outline;
            const std::uint8_t* px = image.pixel(x, y);
            if (r < 0.8) {
                // Water: blue dominates, unlike the colour map's greens and yellows.
                EXPECT_GT(px[2], px[0]) << x << "," << y;
                EXPECT_GE(px[2], px[1]) << x << "," << y;
                water += difference(px, kBackground) > 8;
            } else if (r > 1.3 && x < legendBarRect(kWidth, kHeight).left - 60) {
                EXPECT_LE(difference(px, kBackground), 1) << x << "," << y;
            }
        }
    }
    EXPECT_GT(water, 1000u);
}

TEST_F(OffscreenRender, ObstaclesAndContainerAreDrawn) {
    SceneGeometry geometry;
    geometry.container = {{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}};
    geometry.obstacleBoxes.push_back({{-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}});
    renderer_->setGeometry(geometry);
    renderer_->setShowLegend(false);
    OrbitCamera camera = frontCamera();
    camera.distance = 3;
    const Image image = renderer_->renderImage(camera, kWidth, kHeight);
    // The obstacle at the centre is solid and not background; a container edge is drawn.
    EXPECT_GT(difference(image.pixel(kWidth / 2, kHeight / 2), kBackground), 20);
    const PixelPoint corner = projectToPixel(camera, Vec3d(0.5, 0, 0.5), kWidth, kHeight);
    bool edge = false;
    for (int dx = -2; dx <= 2; ++dx) {
        edge = edge || difference(image.pixel(int(corner.x) + dx, int(corner.y)), kBackground) > 20;
    }
    EXPECT_TRUE(edge) << "no container edge near pixel " << corner.x << "," << corner.y;
}

// A rigid body is drawn where its pose puts it, not where the scene started it: a long thin box
// turned a quarter turn about z stands upright; the pixels above and below the centre are solid,
// those beside it background.
TEST_F(OffscreenRender, BodiesAreDrawnAtTheirPose) {
    SceneGeometry geometry;
    geometry.container = {{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}};
    BodySpec plank;
    plank.box = {{-0.3, -0.03, -0.03}, {0.3, 0.03, 0.03}};  // lying along x at the start
    geometry.bodies.push_back(plank);
    OrbitCamera camera = frontCamera();
    camera.distance = 3;
    const Image image = renderUpright(geometry, camera);
    const PixelPoint top = projectToPixel(camera, Vec3d(0, 0.2, 0), kWidth, kHeight);
    const PixelPoint side = projectToPixel(camera, Vec3d(0.2, 0, 0), kWidth, kHeight);
    EXPECT_GT(difference(image.pixel(int(top.x), int(top.y)), kBackground), 20);
    EXPECT_LE(difference(image.pixel(int(side.x), int(side.y)), kBackground), 1);
}

// A mesh body is drawn about its centre of mass at its pose: the same plank as a 12-triangle mesh
// starting away from the origin (centroid at x = 0.2), posed at the origin a quarter turn about z.
TEST_F(OffscreenRender, MeshBodiesAreDrawnAboutTheirCentreAtTheirPose) {
    SceneGeometry geometry;
    geometry.container = {{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}};
    BodySpec plank;
    plank.isMesh = true;
    for (int c = 0; c < 8; ++c) {
        plank.mesh.vertices.push_back(
            Vec3d((c & 1) ? 0.5 : -0.1, (c & 2) ? 0.03 : -0.03, (c & 4) ? 0.03 : -0.03));
    }
    const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        plank.mesh.triangles.push_back({q[0], q[1], q[2]});
        plank.mesh.triangles.push_back({q[0], q[2], q[3]});
    }
    plank.solid = meshSolidOf(plank.mesh.vertices, plank.mesh.triangles);
    ASSERT_NEAR(plank.centre().x, 0.2, 1e-12);
    geometry.bodies.push_back(plank);
    OrbitCamera camera = frontCamera();
    camera.distance = 3;
    const Image image = renderUpright(geometry, camera);
    // Centred, it spans y = -0.3 .. 0.3; drawn about the mesh's own origin it would span
    // -0.1 .. 0.5, and y = -0.25 would be background.
    const PixelPoint top = projectToPixel(camera, Vec3d(0, 0.2, 0), kWidth, kHeight);
    const PixelPoint bottom = projectToPixel(camera, Vec3d(0, -0.25, 0), kWidth, kHeight);
    const PixelPoint above = projectToPixel(camera, Vec3d(0, 0.4, 0), kWidth, kHeight);
    const PixelPoint side = projectToPixel(camera, Vec3d(0.2, 0, 0), kWidth, kHeight);
    EXPECT_GT(difference(image.pixel(int(top.x), int(top.y)), kBackground), 20);
    EXPECT_GT(difference(image.pixel(int(bottom.x), int(bottom.y)), kBackground), 20);
    EXPECT_LE(difference(image.pixel(int(above.x), int(above.y)), kBackground), 1);
    EXPECT_LE(difference(image.pixel(int(side.x), int(side.y)), kBackground), 1);
}

TEST(PngImage, WritesAndReadsBackExactly) {
    Image image(37, 21);
    for (std::size_t i = 0; i < image.rgb.size(); ++i) {
        image.rgb[i] = std::uint8_t((i * 7919) % 251);
    }
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("weir_png_" + std::to_string(::getpid()) + ".png"))
                                 .string();
    writePng(path, image);
    const Image back = readPng(path);
    std::filesystem::remove(path);
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 21);
    EXPECT_EQ(back.rgb, image.rgb);
    EXPECT_THROW(readPng(path), IoError);
}

}  // namespace
}  // namespace weir
