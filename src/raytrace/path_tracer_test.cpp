// Physics of the water look: the sky a ray sees when it meets nothing, Fresnel reflectance and
// Snell refraction against their closed forms, Beer-Lambert absorption through a slab of water
// looked at from above, and the tone curve's ends.
#include "raytrace/path_tracer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "raytrace/raytrace_test_support.h"
#include "raytrace/water_renderer.h"

namespace weir {
namespace {

constexpr float kWater = 1.333f;

// A closed box of water, wound counter-clockwise seen from outside, a normal per face.
TriangleMesh waterBox(const Box& box) {
    TriangleMesh mesh;
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            Vec3f n;
            n[axis] = side ? 1.0f : -1.0f;
            const auto first = std::uint32_t(mesh.positions.size());
            for (int k = 0; k < 4; ++k) {
                Vec3f p;
                p[axis] = float(side ? box.max[axis] : box.min[axis]);
                p[u] = float((k == 1 || k == 2) ? box.max[u] : box.min[u]);
                p[v] = float(k >= 2 ? box.max[v] : box.min[v]);
                mesh.positions.push_back(p);
                mesh.normals.push_back(n);
            }
            const std::uint32_t ccw[2][6] = {{0, 3, 2, 0, 2, 1}, {0, 1, 2, 0, 2, 3}};
            for (std::uint32_t k : ccw[side]) {
                mesh.indices.push_back(first + k);
            }
        }
    }
    return mesh;
}

// A look lit by the sun alone (no sky, no glow), one colour of floor.
WaterLook sunOnlyLook() {
    WaterLook look;
    look.skyZenith = look.skyHorizon = look.skyBelowHorizon = look.sunGlow = Vec3f();
    look.floorLight = look.floorDark = look.groundAlbedo = Vec3f(0.8f, 0.6f, 0.4f);
    return look;
}

TEST(WaterLook, ARayThatMeetsNothingSeesTheSky) {
    WaterLook look;
    look.sunGlow = Vec3f();
    // The gradient's ends: the zenith straight up, the horizon level.
    const Vec3f up = skyRadiance(look, Vec3f(0, 1, 0), true);
    const Vec3f level = skyRadiance(look, normalized(Vec3f(1, 0, 0.3f)), true);
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(up[c], look.skyZenith[c]);
        EXPECT_FLOAT_EQ(level[c], look.skyHorizon[c]);
    }
    // Halfway up in sin(elevation): sqrt(1/2) of the way from the horizon to the zenith.
    const Vec3f mid = skyRadiance(look, normalized(Vec3f(std::sqrt(3.0f), 1, 0)), true);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(mid[c],
                    look.skyHorizon[c] + (look.skyZenith[c] - look.skyHorizon[c]) * std::sqrt(0.5f),
                    1e-5f);
    }

    // Traced: rays that rise from above an empty container meet nothing and see that sky.
    const TracingScene scene(
        {nullptr, Box{{0, 0, 0}, {1, 1, 1}}, {}, {}, {}, {}, {}, Vec3d(3, 2, 3), 0});
    look = WaterLook();
    for (const Vec3f d :
         {Vec3f(0, 1, 0), normalized(Vec3f(0.3f, 0.2f, -1)), normalized(look.sunDirection)}) {
        SampleStream random(0, 0);
        const Vec3f seen =
            traceRadiance(scene.view(), look, {Vec3f(0.5f, 1.5f, 0.5f), d}, false, random);
        const Vec3f sky = skyRadiance(look, d, true);
        for (int c = 0; c < 3; ++c) {
            EXPECT_FLOAT_EQ(seen[c], sky[c]);
        }
    }
}

TEST(WaterLook, SunDiscGivesTheSunsIrradiance) {
    // The disc that specular paths see and the sun that matte surfaces sample directly are one
    // light: the disc's radiance integrated over directions about the sun (a cone twice its size,
    // by Monte Carlo) gives the irradiance on a surface facing the sun.
    WaterLook look;
    look.skyZenith = look.skyHorizon = look.skyBelowHorizon = look.sunGlow = Vec3f();
    const Vec3f sun = normalized(look.sunDirection);
    const float cone = 2.0f * look.sunAngularRadius;
    const float solidAngle = 2.0f * kPiF * oneMinusCos(cone);
    double irradiance = 0;
    const int n = 200000;
    SampleStream random(7, 0);
    for (int k = 0; k < n; ++k) {
        const float u1 = random.next();
        const float u2 = random.next();
        const Vec3f d = directionInCone(sun, cone, u1, u2);
        irradiance += double(skyRadiance(look, d, true).x) * double(dot(d, sun));
    }
    irradiance *= double(solidAngle) / n;
    EXPECT_NEAR(irradiance, double(look.sunIrradiance.x), 0.01 * double(look.sunIrradiance.x));
    // Without the disc (after a matte bounce): nothing left.
    EXPECT_EQ(skyRadiance(look, sun, false).x, 0.0f);
}

TEST(WaterLook, FresnelReflectanceMatchesClosedForms) {
    // Normal incidence, either way: ((n - 1) / (n + 1))^2 = 0.0204.
    const float normal = (kWater - 1) * (kWater - 1) / ((kWater + 1) * (kWater + 1));
    EXPECT_NEAR(normal, 0.0204f, 5e-5f);
    EXPECT_NEAR(fresnelReflectance(1.0f, 1.0f, kWater), normal, 1e-6f);
    EXPECT_NEAR(fresnelReflectance(1.0f, kWater, 1.0f), normal, 1e-6f);
    // Grazing: everything reflected.
    EXPECT_NEAR(fresnelReflectance(0.0f, 1.0f, kWater), 1.0f, 1e-6f);
    // From inside: total beyond the critical angle asin(1 / n) = 48.6 degrees, not before.
    const float critical = std::asin(1.0f / kWater);
    EXPECT_NEAR(critical * 180 / kPiF, 48.6f, 0.05f);
    EXPECT_EQ(fresnelReflectance(std::cos(critical + 0.01f), kWater, 1.0f), 1.0f);
    EXPECT_EQ(fresnelReflectance(std::cos(1.2f), kWater, 1.0f), 1.0f);
    EXPECT_LT(fresnelReflectance(std::cos(critical - 0.01f), kWater, 1.0f), 0.6f);
    // Brewster's angle atan(n): p-polarised light passes entirely, so the reflectance is half the
    // s-reflectance, sin^2(i - t) / sin^2(i + t) with i + t = 90 degrees.
    const float brewster = std::atan(kWater);
    const float refractedAngle = 0.5f * kPiF - brewster;
    const float s = std::sin(brewster - refractedAngle);
    EXPECT_NEAR(fresnelReflectance(std::cos(brewster), 1.0f, kWater), 0.5f * s * s, 1e-5f);
}

TEST(WaterLook, RefractionFollowsSnellsLaw) {
    const Vec3f n(0, 1, 0);
    for (float degrees : {0.0f, 20.0f, 45.0f, 80.0f}) {
        const float i = degrees * kPiF / 180;
        const Vec3f d(std::sin(i), -std::cos(i), 0);
        Vec3f t;
        ASSERT_TRUE(refracted(d, n, 1.0f / kWater, t));
        EXPECT_NEAR(std::sqrt(t.x * t.x + t.z * t.z), std::sin(i) / kWater, 1e-5f);  // sin t
        EXPECT_LT(t.y, 0.0f);
        EXPECT_NEAR(length(t), 1.0f, 1e-5f);
    }
    // From the water, past the critical angle: no refracted ray.
    Vec3f t(9, 9, 9);
    EXPECT_FALSE(refracted(Vec3f(std::sin(0.9f), std::cos(0.9f), 0), Vec3f(0, -1, 0), kWater, t));
    EXPECT_EQ(t.x, 9.0f);
}

TEST(WaterLook, SlabOfWaterTintsTheFloorByBeerLambert) {
    // A slab of water L deep on the floor of a 2 x 1 x 2 m container, seen straight down from
    // above its middle. The sun, 20 degrees from the zenith, is the only light, and the floor
    // reflects it straight back (no bounces). The pixel: the floor's albedo / pi times the sun's
    // irradiance at 20 degrees, times the light's way down (Fresnel transmission at 20 degrees,
    // then L / cos 20 in the water) and the view's way up (L, then Fresnel transmission at normal
    // incidence); the 2% that the surface reflects sees the black sky.
    const float depth = 0.5f;
    const Box container{{0, 0, 0}, {2, 1, 2}};
    const TriangleMesh slab = waterBox({{0, 0, 0}, {2, double(depth), 2}});
    // The slab's bottom and sides lie on the floor and walls: where the water touches them.
    TracingSceneDescription description{&slab, container, {}, {}, {}, {}, {}, Vec3d(1, 3, 1), 0.01};
    const TracingScene scene(description);
    EXPECT_EQ(scene.waterTriangles(), 2u);  // the top
    EXPECT_EQ(scene.contactTrianglesLeftOut(), 10u);

    WaterLook look = sunOnlyLook();
    const float sunAngle = 20.0f * kPiF / 180;
    look.sunDirection = Vec3f(std::sin(sunAngle), std::cos(sunAngle), 0);
    look.sunAngularRadius = 1e-4f;
    look.maxDiffuseBounces = 0;
    const int samples = 6000;
    Vec3f sum;
    for (int k = 0; k < samples; ++k) {
        SampleStream random(12345, std::uint32_t(k));
        sum += traceRadiance(scene.view(), look, {Vec3f(1.0f, 2.5f, 1.0f), Vec3f(0, -1, 0)}, false,
                             random);
    }
    const Vec3f seen = sum * (1.0f / samples);
    const float cosSun = std::cos(sunAngle);
    const float down = 1 - fresnelReflectance(cosSun, 1, kWater);
    const float up = 1 - fresnelReflectance(1, kWater, 1);
    for (int c = 0; c < 3; ++c) {
        const float sigma = look.absorption[c];
        const float expected = look.floorLight[c] / kPiF * look.sunIrradiance[c] * cosSun * down *
                               std::exp(-sigma * depth / cosSun) * std::exp(-sigma * depth) * up;
        EXPECT_NEAR(seen[c], expected, 0.01f * expected) << "channel " << c;
    }
    // The same floor without the water: the light's and the view's absorption and transmissions
    // gone.
    const TracingScene dry({nullptr, container, {}, {}, {}, {}, {}, Vec3d(1, 3, 1), 0.01});
    SampleStream random(1, 0);
    const Vec3f bare =
        traceRadiance(dry.view(), look, {Vec3f(1.0f, 2.5f, 1.0f), Vec3f(0, -1, 0)}, false, random);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(bare[c], look.floorLight[c] / kPiF * look.sunIrradiance[c] * cosSun,
                    1e-4f * bare[c]);
    }
}

TEST(WaterLook, LightInsideTheWaterIsTrappedBeyondTheCriticalAngle) {
    // From inside a deep pool, looking up at 60 degrees from the vertical (past 48.6): the surface
    // reflects everything, so the ray never reaches the sky; at 30 degrees most of it does.
    const Box container{{0, 0, 0}, {40, 10, 40}};
    const TriangleMesh pool = waterBox({{0, 0, 0}, {40, 5, 40}});
    const TracingScene scene({&pool, container, {}, {}, {}, {}, {}, Vec3d(20, 20, 20), 0.01});
    WaterLook look;
    look.absorption = Vec3f();
    look.sunGlow = Vec3f();
    look.sunIrradiance = Vec3f();  // the sky alone
    look.maxDiffuseBounces = 0;    // the pool's floor and walls: black
    look.skyZenith = look.skyHorizon = Vec3f(1, 1, 1);
    auto throughSurface = [&](float degrees) {
        const float a = degrees * kPiF / 180;
        double sum = 0;
        for (int k = 0; k < 2000; ++k) {
            SampleStream random(3, std::uint32_t(k));
            sum +=
                traceRadiance(scene.view(), look,
                              {Vec3f(20, 4, 20), Vec3f(std::sin(a), std::cos(a), 0)}, true, random)
                    .x;
        }
        return sum / 2000;
    };
    EXPECT_EQ(throughSurface(60), 0.0);
    const float cos30 = std::cos(30 * kPiF / 180);
    EXPECT_NEAR(throughSurface(30), 1 - fresnelReflectance(cos30, kWater, 1), 0.01);
}

TEST(WaterLook, ToneCurveMapsBlackToBlackAndSaturatesBrightLight) {
    EXPECT_EQ(toneMappedByte(0.0f, 1.0f), 0);
    EXPECT_EQ(toneMappedByte(1000.0f, 1.0f), 255);
    EXPECT_LT(toneMappedByte(0.18f, 1.0f), toneMappedByte(0.36f, 1.0f));
    EXPECT_EQ(toneMappedByte(0.18f, 2.0f), toneMappedByte(0.36f, 1.0f));
}

TEST(WaterLook, ImagesOfConsecutivePathsAddUpToTheImageOfAll) {
    // Motion blur traces time slices with consecutive shares of the paths (firstSample): paths
    // 0-4 and 5-15, weighted by 5 and 11, are the image of paths 0-15.
    const TriangleMesh ball = testing::waterBall(Vec3f(0.5f, 0.45f, 0.5f), 0.25f);
    TracingSceneDescription description;
    description.water = &ball;
    description.container = {{0, 0, 0}, {1, 1, 1}};
    description.cameraEye = Vec3d(0.5, 1.4, 2.2);
    const TracingScene scene(description);
    const int width = 24, height = 16;
    const PinholeCamera camera =
        testing::lookAt(Vec3f(description.cameraEye), Vec3f(0.5f, 0.4f, 0.5f), width, height);
    const WaterLook look;
    const auto all = traceWaterImage(Backend::Cpu, scene, look, camera, width, height, 16);
    const auto first = traceWaterImage(Backend::Cpu, scene, look, camera, width, height, 5);
    const auto rest = traceWaterImage(Backend::Cpu, scene, look, camera, width, height, 11, 5);
    const auto other = traceWaterImage(Backend::Cpu, scene, look, camera, width, height, 11, 7);
    double worst = 0, shifted = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const double sum = (5.0 * first[i][c] + 11.0 * rest[i][c]) / 16.0;
            worst = std::max(worst, std::abs(sum - all[i][c]) / std::max(0.05, double(all[i][c])));
            shifted = std::max(shifted, std::abs(double(other[i][c] - rest[i][c])));
        }
    }
    EXPECT_LT(worst, 1e-5);
    EXPECT_GT(shifted, 1e-3);  // other paths are other random numbers
}

}  // namespace
}  // namespace weir
