// On a GPU: the hierarchy built on the device is the host reference's, node for node, and finds
// the nearest of all triangles for random rays; a frame of the live water look, accumulated over
// several renders, is the offline CUDA tracer's image of the same mesh (the same paths, so equal
// up to float rounding and ties between triangles); and particles on the device give the surface
// the host path gives them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/backend.h"
#include "raytrace/interactive_water.h"
#include "raytrace/lbvh.h"
#include "raytrace/raytrace_test_support.h"
#include "raytrace/water_renderer.h"
#include "surface/surface_test_support.h"

namespace weir {
namespace {

using namespace weir::testing;

std::vector<BvhTriangle> randomTriangles(std::size_t n, std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), small(-0.03f, 0.03f),
        large(-0.4f, 0.4f);
    std::vector<BvhTriangle> triangles;
    for (std::size_t t = 0; t < n; ++t) {
        const Vec3f centre(unit(rng), unit(rng), unit(rng));
        auto& spread = t % 50 == 0 ? large : small;
        Vec3f p[3];
        for (Vec3f& c : p) {
            c = centre + Vec3f(spread(rng), spread(rng), spread(rng));
        }
        triangles.push_back({p[0], p[1] - p[0], p[2] - p[0]});
    }
    return triangles;
}

TEST(LbvhCuda, DeviceBuildIsTheHostBuildAndFindsTheNearestHits) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP()
            << "no CUDA device visible: the hierarchy's CUDA build runs on GPU machines only";
    }
    std::mt19937 rng(23);
    for (std::size_t n : {1u, 2u, 7u, 1000u, 200000u}) {
        const std::vector<BvhTriangle> triangles = randomTriangles(n, rng);
        const HostLbvh device = buildLbvhOnDevice(triangles);
        const HostLbvh host = buildLbvhOnHost(triangles);
        ASSERT_EQ(device.nodes.size(), host.nodes.size()) << n << " triangles";
        ASSERT_EQ(device.order, host.order) << n << " triangles: the Morton order differs";
        std::size_t sameNodes = 0;
        for (std::size_t k = 0; k < host.nodes.size(); ++k) {
            const BvhNode &a = device.nodes[k], &b = host.nodes[k];
            sameNodes += a.first == b.first && a.count == b.count && a.lo.x == b.lo.x &&
                         a.lo.y == b.lo.y && a.lo.z == b.lo.z && a.hi.x == b.hi.x &&
                         a.hi.y == b.hi.y && a.hi.z == b.hi.z;
        }
        EXPECT_EQ(sameNodes, host.nodes.size()) << n << " triangles";
        // The device's hierarchy, walked on the host, against every triangle.
        std::uniform_real_distribution<float> around(-0.5f, 1.5f), normal(-1.0f, 1.0f);
        int hits = 0;
        for (int r = 0; r < 2000; ++r) {
            Ray ray{Vec3f(around(rng), around(rng), around(rng)),
                    Vec3f(normal(rng), normal(rng), normal(rng))};
            if (!(length(ray.direction) > 0.05f)) {
                continue;
            }
            ray.direction = normalized(ray.direction);
            RayHit want;
            want.t = INFINITY;
            for (std::size_t t = 0; t < triangles.size(); ++t) {
                float hitT, u, v;
                if (intersectTriangle(triangles[t], ray, 0.0f, want.t, hitT, u, v)) {
                    want = {hitT, std::int32_t(t), u, v};
                }
            }
            const RayHit got = closestHit(device.view(), ray, 0.0f, INFINITY);
            ASSERT_EQ(got.triangle >= 0, want.triangle >= 0) << n << " triangles, ray " << r;
            if (want.triangle >= 0) {
                ++hits;
                EXPECT_FLOAT_EQ(got.t, want.t) << n << " triangles, ray " << r;
            }
        }
        if (n >= 1000) {
            EXPECT_GT(hits, 100) << n << " triangles";
        }
    }
}

TEST(InteractiveWaterCuda, AccumulatedFrameIsTheOfflineImage) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device visible: the live water look runs on GPU machines only";
    }
    // The ball sits on the floor: its lowest faces lie on it and are left out, in both.
    const TriangleMesh ball = waterBall(Vec3f(0.5f, 0.25f, 0.5f), 0.25f);
    TracingSceneDescription description;
    description.water = &ball;
    description.container = {{0, 0, 0}, {1, 1, 1}};
    description.obstacleBoxes = {{{0.05, 0, 0.05}, {0.25, 0.3, 0.25}}};
    description.cameraEye = Vec3d(0.5, 1.4, 2.2);
    description.contactDistance = 0.02;
    const int width = 96, height = 64, samples = 32, frames = 4;
    const PinholeCamera camera =
        lookAt(Vec3f(description.cameraEye), Vec3f(0.5f, 0.3f, 0.5f), width, height);
    const WaterLook look;
    const TracingScene scene(description);
    const std::vector<Vec3f> offline =
        traceWaterImage(Backend::Cuda, scene, look, camera, width, height, samples);

    InteractiveWaterSetup setup;
    setup.scene = description;
    setup.surface.spacing = 0.02;
    setup.look = look;
    setup.width = width;
    setup.height = height;
    setup.pathsPerFrame = samples / frames;
    InteractiveWater live(setup);
    live.setMesh(ball);
    live.setCamera(camera);
    for (int f = 0; f < frames; ++f) {
        live.render();
    }
    EXPECT_EQ(live.pathsPerPixel(), samples);
    EXPECT_EQ(std::size_t(live.times().triangles), scene.shading().size());
    const std::vector<Vec3f> image = live.radiance();
    ASSERT_EQ(image.size(), offline.size());
    double offlineSum = 0, liveSum = 0;
    std::size_t close = 0;
    for (std::size_t i = 0; i < image.size(); ++i) {
        float worst = 0;
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(image[i][c] - offline[i][c]) /
                                        std::max(0.05f, std::abs(offline[i][c])));
        }
        close += worst < 1e-3f;
        offlineSum += double(offline[i].x + offline[i].y + offline[i].z);
        liveSum += double(image[i].x + image[i].y + image[i].z);
    }
    EXPECT_GT(double(close), 0.95 * double(image.size()))
        << close << " of " << image.size() << " pixels agree within 0.1%";
    EXPECT_NEAR(liveSum, offlineSum, 0.005 * offlineSum);
    // The tone-mapped bytes are the offline mapping's.
    const std::vector<std::uint8_t> rgb = live.rgb();
    const std::vector<std::uint8_t> expected = toneMapToSrgb8(image, look.exposure);
    std::size_t sameBytes = 0;
    for (std::size_t i = 0; i < rgb.size(); ++i) {
        sameBytes += std::abs(int(rgb[i]) - int(expected[i])) <= 1;
    }
    EXPECT_EQ(sameBytes, rgb.size());

    // A moved camera starts the accumulation again.
    live.setCamera(lookAt(Vec3f(0.6f, 1.4f, 2.2f), Vec3f(0.5f, 0.3f, 0.5f), width, height));
    live.render();
    EXPECT_EQ(live.pathsPerPixel(), samples / frames);
}

TEST(InteractiveWaterCuda, ParticlesOnTheDeviceGiveTheHostPathsSurface) {
    if (!cudaDeviceAvailable()) {
        GTEST_SKIP() << "no CUDA device visible: the live water look runs on GPU machines only";
    }
    // A ball of fluid resting on the floor and a slab in a corner.
    const double d = 0.02;
    HostParticles particles = testing::latticeBall(Vec3d(0.5, 0.3, 0.5), 0.2, d);
    const int counts[3] = {20, 5, 10};
    testing::appendPositions(particles, testing::latticeBox(Vec3d(0, 0, 0), counts, d));
    TracingSceneDescription description;
    description.container = {{0, 0, 0}, {1, 1, 1}};
    description.contactDistance = d;
    description.cameraEye = Vec3d(0.5, 1.4, 2.2);
    InteractiveWaterSetup setup;
    setup.scene = description;
    setup.surface.spacing = d;
    setup.surface.removeSlivers = false;
    setup.width = 64;
    setup.height = 48;
    InteractiveWater live(setup);
    live.setCamera(lookAt(Vec3f(description.cameraEye), Vec3f(0.5f, 0.3f, 0.5f), 64, 48));
    live.setHostParticles(particles);  // uploaded, then the device path
    live.render();
    EXPECT_GT(live.times().surfaceMs, 0.0);
    EXPECT_GT(live.times().bvhMs, 0.0);

    // The host path: the same plan (the same bounds), the CUDA surface downloaded, its faces on
    // the floor and walls left out by the offline scene.
    SurfacePlan plan = planSurface(particles, setup.surface);
    const TriangleMesh mesh = reconstructSurface(Backend::Cuda, particles, plan);
    description.water = &mesh;
    const TracingScene scene(description);
    ASSERT_GT(scene.waterTriangles(), 1000u);
    EXPECT_EQ(std::size_t(live.times().triangles), scene.waterTriangles());
    EXPECT_GT(scene.contactTrianglesLeftOut(), 100u);

    // Standing still, the image refines: the surface is not built again.
    live.render();
    EXPECT_EQ(live.pathsPerPixel(), 2);
    EXPECT_EQ(live.times().surfaceMs, 0.0);
}

}  // namespace
}  // namespace weir
